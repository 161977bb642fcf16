"""Kontur: motion interpolation for CNC machines and robots, from Python.

The same library as the ``kontur`` command, compiled into ``kontur._core``:

* curves: :class:`NurbsCurve` (evaluation, length, u(s), span polynomials, forward
  differences), :func:`read_curve`;
* arcs: :func:`circle_through_points`, :func:`conic_through_points` with the fields of the seed
  programs' reports and their motion tables (:meth:`Arc.steps`);
* programs: :class:`Machine`, :func:`check`, :func:`run` (setpoints as one numpy structured
  array), :func:`run_iter` (the same in chunks), :func:`verify` (setpoints of any planner).

Units everywhere: lengths [mm], angles [rad] (rotary axes of a machine [deg]), times [s], path
speeds [mm/s], feeds F [mm/min]. A curve, program or machine that breaks a rule raises
:class:`InputError`, a ``ValueError`` with the command's message (file, line, rule) and the rule's
short name in ``rule``. numpy is imported on first use, so ``import kontur`` works without it.
"""

from __future__ import annotations

import json
import math
import os
from typing import Iterator, Optional, Sequence, Union

from . import _core

__all__ = [
    "__version__",
    "InputError",
    "NurbsCurve",
    "read_curve",
    "Arc",
    "Steps",
    "circle_through_points",
    "conic_through_points",
    "Machine",
    "check",
    "Run",
    "run",
    "RunIterator",
    "run_iter",
    "verify",
    "setpoint_dtype",
]

#: The library's version (the same as ``kontur --version``).
__version__: str = _core.__version__

#: A broken rule of an input: a ``ValueError`` whose message is the command's and whose ``rule``
#: attribute is the rule's stable short name (``"knot-count"``, ``"points-collinear"`` ...).
InputError = _core.InputError

PathLike = Union[str, "os.PathLike[str]"]


def _np():
    try:
        import numpy
    except ImportError as error:  # pragma: no cover - numpy is a dependency of the package
        raise ImportError(
            "kontur needs numpy for its arrays: on Debian `sudo apt-get install python3-numpy` "
            "(for /usr/bin/python3), else `python3 -m pip install numpy`"
        ) from error
    return numpy


def _doubles(values, ndim: Optional[int] = None, what: str = "values"):
    """values as a float64 numpy array, C-contiguous (no copy when it already is one; a number stays 0-d)."""
    np = _np()
    try:
        a = np.asarray(values, dtype=np.float64)
        if a.ndim and not a.flags.c_contiguous:
            a = np.ascontiguousarray(a)
    except (TypeError, ValueError) as error:
        raise InputError(f"{what}: not an array of numbers ({error})") from None
    if ndim is not None and a.ndim != ndim:
        raise InputError(f"{what}: expected {ndim} dimension(s), got an array of shape {a.shape}")
    return a


def _over(values, what: str, compute):
    """``compute`` (a compiled function of a flat float64 array) over ``values`` of any shape: the
    result has their shape, then the shape of each value's result (a float for a number that maps
    to one value)."""
    np = _np()
    a = _doubles(values, None, what)
    out = np.asarray(compute(np.ascontiguousarray(a.reshape(-1))))
    out = out.reshape(a.shape + out.shape[1:])
    return float(out) if out.ndim == 0 else out


# ----------------------------------------------------------------------------------- curves


class NurbsCurve:
    """A NURBS or B-spline curve of degree 1..9 with a clamped knot vector, in 2-D or 3-D.

    ``NurbsCurve(degree=3, knots=[...], points=[[x, y], ...] or [[x, y, z], ...], weights=None)``
    checks every rule of the definition (knot count = points + degree + 1, knots non-decreasing,
    end multiplicity degree + 1, weights > 0, ...) and raises :class:`InputError` naming the rule
    and the value. Coordinates [mm]; the parameter u is the knot vector's, [u_min, u_max].
    """

    def __init__(self, degree: int, knots: Sequence[float], points, weights: Optional[Sequence[float]] = None):
        np = _np()
        p = _doubles(points, 2, "points")
        if p.shape[1] not in (2, 3):
            raise InputError(f"points: expected [x, y] or [x, y, z] per point, got {p.shape[1]} coordinates")
        #: 2 when the points were given as [x, y] (evaluate then returns x, y), else 3.
        self.dimension: int = int(p.shape[1])
        if self.dimension == 2:
            p = np.ascontiguousarray(np.column_stack([p, np.zeros(len(p))]))
        w = [] if weights is None else [float(x) for x in _doubles(weights, 1, "weights")]
        self._c = _core.NurbsCurve(int(degree), [float(k) for k in _doubles(knots, 1, "knots")], p, w)

    @classmethod
    def _wrap(cls, core, dimension: int) -> "NurbsCurve":
        self = cls.__new__(cls)
        self._c = core
        self.dimension = dimension
        return self

    # -- the definition
    @property
    def degree(self) -> int:
        """Polynomial degree p (order p + 1)."""
        return self._c.degree

    @property
    def knots(self):
        """The knot vector (numpy array)."""
        return _np().asarray(self._c.knots)

    @property
    def points(self):
        """Control points [mm], shape (n, dimension)."""
        return _np().asarray(self._c.points)[:, : self.dimension]

    @property
    def weights(self):
        """Weights, one per control point (all 1 for a B-spline)."""
        return _np().asarray(self._c.weights)

    @property
    def rational(self) -> bool:
        """True when the weights are not all equal."""
        return self._c.rational

    @property
    def u_min(self) -> float:
        """First parameter of the curve."""
        return self._c.u_min

    @property
    def u_max(self) -> float:
        """Last parameter of the curve."""
        return self._c.u_max

    @property
    def breakpoints(self):
        """The distinct knots from u_min to u_max (span boundaries)."""
        return _np().asarray(self._c.breakpoints)

    def __repr__(self) -> str:
        return (
            f"NurbsCurve(degree={self.degree}, points={len(self._c.weights)}, dimension={self.dimension}, "
            f"rational={self.rational}, u=[{self.u_min:g}, {self.u_max:g}])"
        )

    # -- evaluation
    def evaluate(self, u, derivatives: int = 0):
        """The point C(u) [mm], and with ``derivatives`` = k also C'(u) .. C^(k)(u) (k <= 3).

        ``u`` is a number or an array of parameters in [u_min, u_max] (outside: InputError; never
        clamped). Returns, for a number, shape (dimension,) when derivatives = 0, else
        (derivatives + 1, dimension) with row j the j-th derivative [mm per parameter unit^j];
        for an array of shape S, S + those shapes. Vectorised in C++ (de Boor, Piegl & Tiller A2.3),
        without the GIL.
        """
        return _over(u, "u", lambda flat: self._c.evaluate(flat, int(derivatives), self.dimension))

    def __call__(self, u):
        """The point C(u) [mm]: ``evaluate(u)``."""
        return self.evaluate(u)

    # -- length
    def length(self, tolerance: float = 1e-10) -> float:
        """The curve's length [mm] by Kontur's default method: nested Gauss-Kronrod-Patterson rules
        per span, to the relative ``tolerance`` (raised to at least 1e-13)."""
        return self._c.length(float(tolerance))["length"]

    def length_simpson(self, scheme: str = "whole_curve", tolerance: float = 1e-6, max_halvings: int = 20) -> dict:
        """The seed's method (seed 000): composite Simpson with n = 2, 4, 8, ... intervals, stopped
        by Runge's rule |l_2n - l_n| / 15 < tolerance * |l_2n|, result l_2n + (l_2n - l_n) / 15.

        ``scheme``: ``"whole_curve"`` (halving over the whole parameter range: the seed's table) or
        ``"per_span"`` (Simpson-Runge on each knot span, then the sum). Returns a dict: ``length``
        [mm], ``error_estimate`` [mm], ``evaluations`` (of |C'(u)|), ``converged``, and ``history``,
        the seed's table: (n intervals, raw Simpson value l_n [mm]) per halving (whole_curve only).
        """
        return self._c.length_simpson(str(scheme), float(tolerance), int(max_halvings))

    def u_of_s(self, s):
        """The parameter u at arc length s [mm] from the start (s in [0, length]; a number or an
        array), from an arc-length table built on first use (relative accuracy 1e-13)."""
        return _over(s, "s", self._c.u_of_s)

    def s_of_u(self, u):
        """The arc length [mm] from u_min to u (a number or an array), from the same table."""
        return _over(u, "u", self._c.s_of_u)

    # -- the two levels of seed 002
    def span_polynomials(self, global_parameter: bool = False) -> list:
        """Every non-empty knot span as a power-basis polynomial per coordinate (the upper level of
        seed 002). Returns a list of dicts: ``u_start``, ``u_end``, ``knot_index`` (i with
        knots[i] = u_start), ``degree``, ``rational``, and ``coefficients``, shape (4, degree + 1):
        rows w x, w y, w z, w (homogeneous; w = 1 for a B-spline), column k the coefficient of
        t^k [mm per parameter unit^k], t = u - u_start, or t = u with ``global_parameter`` (the
        seed's Table 2; worse conditioned)."""
        np = _np()
        spans = self._c.span_polynomials(bool(global_parameter))
        for s in spans:
            s["coefficients"] = np.asarray(s["coefficients"])
        return spans

    def forward_differences(self, step: float, compensated: bool = False, max_steps: int = 10_000_000) -> dict:
        """The lower level of seed 002: the span polynomials stepped at a constant parameter step
        ``step`` by forward differences (p additions per coordinate per step, re-anchored exactly
        at every span boundary), u_n = u_min + n step, up to u_max.

        ``compensated``: each difference kept as an unevaluated sum of two doubles (drift at the
        rounding level) instead of the seed's plain additions. Returns a dict of arrays: ``u``,
        ``points`` [mm] (shape (n, dimension)) and ``span`` (index of the span of each step).
        More than ``max_steps`` steps is an InputError.
        """
        np = _np()
        u, points, span = self._c.forward_differences(float(step), bool(compensated), self.dimension, int(max_steps))
        return {"u": np.asarray(u), "points": np.asarray(points), "span": np.asarray(span)}

    # -- interpolation at constant feed (seed 004)
    def interpolate(self, feed: float, period: float = 0.001, interpolator: str = "exact",
                    max_steps: int = 10_000_000) -> dict:
        """Steps the curve at constant ``feed`` [mm/min], one setpoint per servo ``period`` [s]:
        each cycle the parameter advances so that the tool moves ds = F T / 60 [mm] (the last
        step ends at u_max). ``interpolator``: ``"exact"`` (Kontur's: the arc-length inverse,
        distances exact to ~1e-12), ``"taylor1"`` or ``"taylor2"`` (seed 004's first- and
        second-order Taylor updates, with their feed fluctuation). Returns a dict of arrays: ``u``,
        ``s`` [mm] (arc length: exact mode measured, Taylor modes the sum of the planned steps)
        and ``points`` [mm] (shape (n, dimension))."""
        np = _np()
        u, s, points = self._c.interpolate(float(feed), float(period), str(interpolator), self.dimension,
                                           int(max_steps))
        return {"u": np.asarray(u), "s": np.asarray(s), "points": np.asarray(points)}

    def feed_fluctuation(self, feed: float, period: float = 0.001, interpolator: str = "exact") -> dict:
        """Seed 004's measure: steps the curve at ``feed`` [mm/min] and ``period`` [s] with the
        ``interpolator`` and measures every cycle's arc length (Gauss-Kronrod, independent of the
        interpolator) against F T / 60. Returns cycles, max_relative and mean_relative
        (|arc / (F T / 60) - 1|), max_chord_error [mm] and final_gap [mm] (what `kontur spline
        --feed` prints)."""
        return self._c.feed_fluctuation(float(feed), float(period), str(interpolator))


def read_curve(path: PathLike) -> NurbsCurve:
    """Reads Kontur's curve file (JSON: ``{"degree": 3, "knots": [...], "points": [[x, y, z], ...],
    "weights": [...]}``, coordinates [mm], the format of ``kontur spline``) and checks it; an error
    names the file, the field, the index and the rule."""
    path = os.fspath(path)
    core = _core.read_curve(path)
    with open(path, encoding="utf-8") as f:
        points = json.load(f)["points"]
    return NurbsCurve._wrap(core, 2 if all(len(p) == 2 for p in points) else 3)


# ----------------------------------------------------------------------------------- arcs


class Steps:
    """A motion table along an arc (:meth:`Arc.steps`).

    Angular mode (``mode == "angular"``, the seed's problem types): ``t`` [s], ``u`` (curve
    parameter), ``angle`` [rad] (central angle of a circle from r1; focal angle of a conic),
    ``points`` [mm] (machine frame, (n, 3)), ``relative`` [mm] (the relative frame of a circle, the
    focal frame of a conic), and the timing ``timing``: problem_type (1 omega given, 2 time given),
    sweep [rad], length [mm], omega [rad/s], time [s], steps N, dt [s], dphi [rad], mean_speed
    V = length / time [mm/s], min_speed, max_speed [mm/s] and speed_variation (max - min) / mean.

    Constant-feed mode (``mode == "constant_feed"``): ``t`` [s], ``s`` [mm] (arc length),
    ``u``, ``points`` [mm], and ``timing``: feed [mm/min], period [s], step F T / 60 [mm], periods,
    time [s], length [mm].
    """

    def __init__(self, mode: str, timing: dict, table):
        self.mode = mode
        self.timing = timing
        self.table = table
        if mode == "angular":
            self.t, self.u, self.angle = table[:, 0], table[:, 1], table[:, 2]
            self.points, self.relative = table[:, 3:6], table[:, 6:9]
        else:
            self.t, self.s, self.u = table[:, 0], table[:, 1], table[:, 2]
            self.points = table[:, 3:6]

    def __len__(self) -> int:
        return len(self.table)

    def __repr__(self) -> str:
        return f"Steps(mode={self.mode!r}, samples={len(self)}, time={self.timing['time']:g} s)"


class Arc:
    """A circle through three points or a conic through five, with every field of the seed
    programs' reports as attributes (see :func:`circle_through_points`,
    :func:`conic_through_points`) and in :meth:`as_dict`."""

    def __init__(self, core):
        np = _np()
        self._c = core
        self._fields = dict(core.fields)
        for name, value in self._fields.items():
            setattr(self, name, np.asarray(value) if isinstance(value, list) else value)

    def as_dict(self) -> dict:
        """The report's fields as plain Python values (lists for points and matrices)."""
        return dict(self._fields)

    def __repr__(self) -> str:
        return f"Arc(kind={self.kind!r}, length={self.length:.9g} mm, sweep={self.sweep:.9g} rad)"

    def steps(
        self,
        *,
        steps: Optional[int] = None,
        omega: Optional[float] = None,
        time: Optional[float] = None,
        feed: Optional[float] = None,
        period: Optional[float] = None,
        max_samples: int = 10_000_000,
    ) -> Steps:
        """The motion along the arc.

        The seed's mode: ``steps=N`` equal steps of the angle (central angle of a circle, focal
        angle of a conic) with either ``omega`` [rad/s] given (problem type 1: t = angle / omega)
        or ``time`` [s] given (type 2: omega = angle / t). Kontur's mode: constant ``feed``
        [mm/min] with one sample per servo ``period`` [s], the arc length exact. Returns
        :class:`Steps`.
        """
        np = _np()
        angular = omega is not None or time is not None
        constant = feed is not None or period is not None
        if angular == constant:
            raise InputError(
                "steps: give either steps=N with omega= or time= (the seed's equal angle steps) or feed= with "
                "period= (constant feed)"
            )
        if angular:
            if (omega is None) == (time is None):
                raise InputError("steps: give one of omega= [rad/s] and time= [s], not both")
            if steps is None:
                raise InputError("steps: the angular mode needs steps=N")
            problem, value = (1, omega) if omega is not None else (2, time)
            timing, table = self._c.angular(problem, float(value), int(steps))
            return Steps("angular", timing, np.asarray(table))
        if feed is None or period is None or steps is not None:
            raise InputError("steps: constant feed needs feed= [mm/min] and period= [s], and no steps=")
        timing, table = self._c.constant_feed(float(feed), float(period), int(max_samples))
        return Steps("constant_feed", timing, np.asarray(table))

    def evaluate(self, u):
        """Points [mm] at curve parameters u (circle: u in [0, 1], angle = sweep u; conic: u is
        the focal angle swept from r1, [0, theta15]); shape (len(u), 3), or (3,) for a number."""
        return _over(u, "u", self._c.evaluate)


def circle_through_points(p1, p2, p3, full_circle: bool = False) -> Arc:
    """The circle through three points in space [mm] (seed 001, program ARC), moving from p1
    through p2 to p3, or with ``full_circle`` the whole circle from p1 back to p1.

    Fields: kind ("circle"), motion_type (1 arc, 2 full circle), points, centre [mm], radius [mm]
    (also a = b = p, eccentricity 0), normal (unit; the motion is counter-clockwise about it), T
    (relative -> machine, 4x4) and T_inverse, relative_points [mm], theta12, theta13, sweep [rad],
    length [mm], end_point [mm]. Coincident or collinear points raise InputError.
    """
    return Arc(_core.circle_through_points(_point(p1, "p1"), _point(p2, "p2"), _point(p3, "p3"), bool(full_circle)))


def conic_through_points(points, plane_tolerance: float = 0.0) -> Arc:
    """The arc of a conic through five points in space [mm], in order along it (seed 001, program
    SOCADI).

    Fields: kind ("ellipse", "circle", "parabola", "hyperbola"), eccentricity, p (focal parameter
    [mm]), a, b, c [mm] (0 for a parabola), centre, vertex, foci, focus [mm], lambda,
    relative_T / relative_T_inverse (the relative frame), relative_points, plane_distance and
    plane_tolerance [mm], coefficients (A, B, C, D, E), rotation [rad], rotated_coefficients
    (A', C', D', E'), axis_angle [rad], branch (hyperbola: +1 / -1), T / T_inverse (focal frame),
    focal_points [mm], focal_angles and swept_angles [rad], theta15 = sweep [rad], length [mm],
    length_error_estimate [mm], end_point. ``plane_tolerance`` [mm]: how far r4, r5 may lie off
    the plane of r1, r2, r3 (0: 1e-9 of the points' extent). Degenerate conics, points off the
    plane or out of order raise InputError.
    """
    pts = [_point(p, f"r{j + 1}") for j, p in enumerate(points)]
    return Arc(_core.conic_through_points(pts, float(plane_tolerance)))


def _point(p, what: str):
    a = _doubles(p, 1, what)
    if a.shape[0] == 2:
        a = _doubles([a[0], a[1], 0.0], 1, what)
    return a


# ----------------------------------------------------------------------------------- machines and programs


def _field(name: str, doc: str, convert=float) -> property:
    """A property of Machine that reads and writes the compiled machine's field ``name`` (read-only
    when ``convert`` is None)."""
    if convert is None:
        return property(lambda self: getattr(self._c, name), doc=doc)
    return property(lambda self: getattr(self._c, name), lambda self, v: setattr(self._c, name, convert(v)), doc=doc)


class Machine:
    """A machine: per-axis velocity [mm/s], acceleration [mm/s^2], jerk [mm/s^3] limits and soft
    limits [mm] (A B C in [deg]), path feed limits, chord and path tolerances [mm], servo period
    [s], the G-code dialect of its control.

    ``Machine.load(path=None)``: None gives Kontur's embedded default (a 3-axis mill at 1 ms);
    a ``.ini`` path is read as a LinuxCNC INI, any other as Kontur's TOML (docs/machine.md).
    Fields may be changed (``m.servo_period_s = 0.000125``, :meth:`set_axis`); a run checks them.
    """

    def __init__(self, core=None):
        self._c = core if core is not None else _core.Machine.default()

    @classmethod
    def load(cls, path: Optional[PathLike] = None) -> "Machine":
        """The machine file ``path`` (LinuxCNC INI or Kontur TOML), or the embedded default."""
        if path is None:
            return cls(_core.Machine.default())
        return cls(_core.Machine.load(os.fspath(path)))

    def copy(self) -> "Machine":
        """An independent copy."""
        return Machine(_core.Machine(self._c))

    name = _field("name", "A name for reports.", str)
    source = _field("source", "Where it was read from (a path, or 'embedded default').", None)
    servo_period_s = _field("servo_period_s", "Servo period [s].")
    max_feed_mm_s = _field("max_feed_mm_s", "Largest programmed path feed honoured [mm/s].")
    rapid_feed_mm_s = _field("rapid_feed_mm_s", "Path speed of G0 moves [mm/s].")
    chord_tolerance_mm = _field("chord_tolerance_mm", "Largest bow height of a servo cycle's chord [mm].")
    path_tolerance_mm = _field("path_tolerance_mm", "G64 tolerance when the program gives none [mm].")
    dialect = _field(
        "dialect",
        "The control's G-code dialect (linuxcnc, fanuc, haas, mitsubishi, sinumerik, grbl, mach3), or None.",
        lambda v: None if v is None else str(v),
    )

    @property
    def axes(self) -> list:
        """The axes in coordinate order, each a dict: name, rotary, max_velocity [mm/s],
        max_acceleration [mm/s^2], max_jerk [mm/s^3], min_position, max_position [mm] (rotary
        axes: [deg] instead of [mm])."""
        return self._c.axes

    def set_axis(self, name: str, **limits) -> None:
        """Changes the limits of axis ``name`` (max_velocity, max_acceleration, max_jerk,
        min_position, max_position, in the units of :attr:`axes`); checked at once."""
        self._c.set_axis(name, **limits)

    def validate(self) -> None:
        """Checks every value (limits finite and > 0, period in [10 us, 100 ms], ...)."""
        self._c.validate()

    def to_toml(self) -> str:
        """The machine as Kontur's TOML (what ``kontur machine`` prints)."""
        return self._c.to_toml()

    def __repr__(self) -> str:
        axes = "".join(a["name"] for a in self.axes)
        return f"Machine(name={self.name!r}, axes={axes!r}, servo_period_s={self.servo_period_s:g}, source={self.source!r})"


def _machine(machine) -> "_core.Machine":
    if machine is None:
        return _core.Machine.default()
    if isinstance(machine, Machine):
        return machine._c
    return _core.Machine.load(os.fspath(machine))


def _args(
    blend: bool = True,
    smooth: bool = True,
    check: bool = True,
    time_optimal: bool = False,
    dialect: Optional[str] = None,
    block_delete: bool = True,
    subroutine_path: Optional[Sequence[PathLike]] = None,
    tool_table: Optional[PathLike] = None,
) -> "_core.RunArgs":
    a = _core.RunArgs()
    a.blend, a.smooth, a.check, a.time_optimal = bool(blend), bool(smooth), bool(check), bool(time_optimal)
    a.dialect = dialect
    a.block_delete = bool(block_delete)
    a.subroutine_path = [os.fspath(p) for p in (subroutine_path or [])]
    a.tool_table = os.fspath(tool_table) if tool_table is not None else ""
    return a


def check(program: PathLike, machine=None, *, blocks: bool = True, **options) -> dict:
    """Reads and validates the part program ``program`` (a G-code file) and returns what
    ``kontur check --json`` prints, as a dict: file, valid, dialect {name, reason}, blocks (per
    block: line, column, n, type, length_mm, feed [mm/min, or 1/min with G93], end [mm] ...;
    empty with ``blocks=False``) and totals (lines, blocks, by_type, path_length_mm,
    rapid_length_mm, dwell_s, warnings ...). The first error raises InputError with the file,
    line, column and rule. ``machine`` (optional) gives the dialect and tool table; ``options``:
    dialect, block_delete, subroutine_path, tool_table (as :func:`run`).
    """
    core_machine = None if machine is None else _machine(machine)
    return json.loads(_core.check(os.fspath(program), core_machine, _args(**options), bool(blocks)))


def setpoint_dtype(axes: str = "XYZ"):
    """The numpy dtype of setpoints with the axis letters ``axes``: ``t`` [s], one float64 field
    per axis named by its lower-case letter ([mm]; a b c [deg]; the V axis is ``v_axis``, since
    ``v`` is the speed), ``v`` (planned path speed [mm/s]) and ``block`` (int64, the source line
    of the block the setpoint lies on), as the CSV's columns t,x,y,z,...,v,block."""
    np = _np()
    fields = [("t", "<f8")]
    for letter in axes:
        name = letter.lower()
        fields.append(("v_axis" if name == "v" else name, "<f8"))
    fields += [("v", "<f8"), ("block", "<i8")]
    return np.dtype(fields)


class Run:
    """The result of :func:`run`: ``setpoints`` (numpy structured array, :func:`setpoint_dtype`),
    ``summary`` (the JSON summary as a dict, the same as ``kontur run --summary``; None with
    check=False), ``passed`` (every limit held), ``total_time_s`` [s], ``axes`` (letters)."""

    def __init__(self, setpoints, result: dict):
        self.setpoints = setpoints
        self.axes: str = result["axes"]
        self.passed: bool = result["passed"]
        self.total_time_s: float = result["total_time_s"]
        self.summary: Optional[dict] = json.loads(result["summary_json"]) if result["summary_json"] else None

    def __len__(self) -> int:
        return len(self.setpoints)

    def __repr__(self) -> str:
        return (
            f"Run(setpoints={len(self.setpoints)}, axes={self.axes!r}, total_time_s={self.total_time_s:g}, "
            f"passed={self.passed})"
        )


def run(program: PathLike, machine=None, **options) -> Run:
    """Runs the part program ``program`` (a G-code file) on ``machine`` (a :class:`Machine`, a
    machine file path, or None for the default): reads it, plans the motion (look-ahead,
    S-curves, corner blends within G64), samples it at the servo period and checks every
    setpoint independently, as ``kontur run``. Returns :class:`Run`, its setpoints in one array.

    ``options``: blend (True; False as ``--no-blend``), smooth (True; ``--no-smooth``), check
    (True: the independent check and the summary), time_optimal (False; ``--time-optimal``),
    dialect (None: the machine's, else detected), block_delete (True), subroutine_path (list of
    folders), tool_table (a tool table file). A program with an error raises InputError before any
    setpoint is made; Ctrl-C stops the run (KeyboardInterrupt).
    """
    data, result = _core.run(os.fspath(program), _machine(machine), _args(**options))
    np = _np()
    return Run(np.frombuffer(data, dtype=setpoint_dtype(result["axes"])), result)


class RunIterator:
    """The setpoints of a run in chunks (:func:`run_iter`): iterate for numpy structured arrays
    of at most ``chunk`` setpoints each. After the last chunk, ``summary``, ``passed`` and
    ``total_time_s`` are set as in :class:`Run`. ``close()`` (or leaving a ``with`` block)
    stops the run early."""

    def __init__(self, stream):
        self._s = stream
        self.axes: str = stream.axes
        self.dtype = setpoint_dtype(self.axes)
        self.summary: Optional[dict] = None
        self.passed: Optional[bool] = None
        self.total_time_s: Optional[float] = None

    def __iter__(self) -> Iterator:
        return self

    def __next__(self):
        data = self._s.next()
        if data is None:
            result = self._s.result()
            if result is not None and self.passed is None:
                self.passed = result["passed"]
                self.total_time_s = result["total_time_s"]
                self.summary = json.loads(result["summary_json"]) if result["summary_json"] else None
            raise StopIteration
        return _np().frombuffer(data, dtype=self.dtype)

    def close(self) -> None:
        """Stops the run (if it still goes on)."""
        self._s.close()

    def __enter__(self) -> "RunIterator":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def run_iter(program: PathLike, machine=None, chunk: int = 100_000, **options) -> RunIterator:
    """:func:`run`, streaming: the planner runs on a thread of its own and hands out chunks of at
    most ``chunk`` setpoints (at most two chunks wait), so memory stays flat for long jobs. The
    program is read and its axes found before this returns (errors of the program itself come
    with the first chunk). Same ``options`` as :func:`run`."""
    return RunIterator(_core.RunStream(os.fspath(program), _machine(machine), _args(**options), int(chunk)))


_AXIS_FIELDS = {letter: letter.lower() for letter in "XYZABCUW"}
_AXIS_FIELDS["V"] = "v_axis"


def verify(program: PathLike, setpoints, machine=None, **options) -> dict:
    """Checks setpoints of any planner against ``program`` and ``machine``, as ``kontur verify``:
    the limits by finite differences, every setpoint's distance from the programmed path, the
    chord error, the start and end. Returns the JSON summary as a dict (``passed`` among its
    fields).

    ``setpoints``: a structured array with a field ``t`` [s] and one per axis (x, y, z, and a b c
    u v_axis w if any) [mm] / [deg], optionally ``v`` [mm/s] and ``block`` (source line; 0 for
    unknown), such as :attr:`Run.setpoints`; a :class:`Run`; or the path of a setpoint file (CSV
    or binary, docs/setpoints.md). ``options``: dialect, block_delete, subroutine_path,
    tool_table, blend, smooth (the path is built as a run builds it).
    """
    np = _np()
    args = _args(**options)
    m = _machine(machine)
    if isinstance(setpoints, Run):
        setpoints = setpoints.setpoints
    if isinstance(setpoints, (str, os.PathLike)):
        return json.loads(_core.verify_file(os.fspath(program), m, args, os.fspath(setpoints))["summary_json"])
    a = np.asarray(setpoints)
    names = a.dtype.names
    if names is None or "t" not in names:
        raise InputError("setpoints: expected a structured array with fields t, x, y, z (..., v, block), "
                         "such as kontur.run(...).setpoints, or a setpoint file's path")
    letters = "".join(letter for letter in "XYZABCUVW" if _AXIS_FIELDS[letter] in names)
    if not any(letter in letters for letter in "XYZ"):
        raise InputError("setpoints: no axis field (x, y, z, ...)")

    def column(name):
        c = a[name]
        return c if c.dtype == np.float64 else c.astype(np.float64)

    n = len(a)
    v = column("v") if "v" in names else np.zeros(n)
    block = column("block") if "block" in names else np.zeros(n)
    result = _core.verify(
        os.fspath(program),
        m,
        args,
        letters,
        column("t"),
        [column(_AXIS_FIELDS[letter]) for letter in letters],
        v,
        block,
        "<setpoints array>",
    )
    return json.loads(result["summary_json"])
