"""Circles through three points and conics through five: the reference vectors of the C++ tests
(tests/test_circle_arc.cpp, tests/test_conic_arc.cpp, methods.md sections 4 and 5), their motion
tables and the rules the points must follow."""

import math

import numpy as np
import pytest

import kontur


def printed(value, reference, decimals):
    assert np.all(np.abs(np.asarray(value) - np.asarray(reference)) <= 0.5 * 10.0 ** (-decimals) + 1e-12)


def to_space(x, y):
    return np.array([100 + x, 200 + 0.6 * y, 300 + 0.8 * y])


def test_circle_reference_vector_1_type_one():
    c = kontur.circle_through_points([110, 100, 50], [100, 110, 50], [90, 100, 50])
    assert c.kind == "circle"
    printed(c.centre, [100, 100, 50], 9)
    assert c.radius == pytest.approx(10.0, abs=1e-12)
    assert c.theta13 == pytest.approx(math.pi, abs=1e-14)
    assert c.theta12 == pytest.approx(math.pi / 2, abs=1e-14)
    printed(c.length, 31.415927, 6)
    s = c.steps(steps=4, omega=0.5)
    printed(s.timing["time"], 6.283185, 6)
    printed(s.timing["mean_speed"], 5.0, 9)
    assert len(s) == 5
    printed(
        s.points,
        [[110, 100, 50], [107.071068, 107.071068, 50], [100, 110, 50], [92.928932, 107.071068, 50], [90, 100, 50]],
        6,
    )
    assert np.allclose(s.angle, np.linspace(0, math.pi, 5), atol=1e-14)
    # The relative frame: X towards r1, the points on the circle of radius R in z = 0.
    assert np.allclose(np.linalg.norm(s.relative[:, :2], axis=1), 10.0, atol=1e-12)
    assert np.allclose(s.relative[:, 2], 0.0, atol=1e-12)


def test_circle_reference_vector_2_type_two():
    c = kontur.circle_through_points((100, 200, 300), (200, 250, 310), (260, 180, 400))
    printed(c.centre, [171.0526316, 171.7611336, 360.6680162], 7)
    printed(c.radius, 97.60388424, 8)
    printed(c.theta13, 2.6669643, 7)
    printed(c.length, 260.3060714, 7)
    s = c.steps(steps=5, time=10.0)
    printed(s.timing["omega"], 0.2666964, 7)
    printed(s.timing["mean_speed"], 26.0306071, 7)
    printed(s.points[1], [138.517634, 233.188777, 292.150597], 6)
    assert np.array_equal(s.points[5], [260, 180, 400])
    assert s.t[5] == pytest.approx(10.0, abs=1e-15)
    T, Ti = np.array(c.T), np.array(c.T_inverse)
    assert np.allclose(T @ Ti, np.eye(4), atol=1e-12)


def test_full_circle_and_constant_feed():
    c = kontur.circle_through_points([10, 0, 0], [0, 10, 0], [-10, 0, 0], full_circle=True)
    assert c.sweep == pytest.approx(2 * math.pi, abs=1e-15)
    assert c.length == pytest.approx(20 * math.pi, abs=1e-12)
    s = c.steps(feed=600.0, period=0.01)  # 0.1 mm per period
    assert s.timing["step"] == pytest.approx(0.1, abs=1e-15)
    arcs = np.diff(s.s)
    assert np.allclose(arcs[:-1], 0.1, atol=1e-12)
    chords = np.linalg.norm(np.diff(s.points, axis=0), axis=1)
    assert np.allclose(chords[:-1], 2 * 10 * np.sin(0.1 / 20), atol=1e-11)
    assert np.array_equal(s.points[-1], [10, 0, 0])


def test_circle_rules():
    with pytest.raises(kontur.InputError) as e:
        kontur.circle_through_points([0, 0, 0], [1, 1, 1], [2, 2, 2])
    assert e.value.rule == "points-collinear"
    with pytest.raises(kontur.InputError) as e:
        kontur.circle_through_points([0, 0, 0], [0, 0, 0], [2, 2, 2])
    assert e.value.rule == "points-coincident"
    c = kontur.circle_through_points([0, 0, 0], [1, 1, 0], [2, 0, 0])
    with pytest.raises(kontur.InputError):
        c.steps(steps=4)
    with pytest.raises(kontur.InputError):
        c.steps(steps=4, omega=1.0, time=2.0)
    with pytest.raises(kontur.InputError) as e:
        c.steps(steps=4, omega=-1.0)
    assert e.value.rule == "omega-positive"


def test_conic_reference_ellipse():
    r = [(105, 200, 300), (104, 201.08, 301.44), (103, 201.44, 301.92), (100, 201.8, 302.4), (96, 201.08, 301.44)]
    k = kontur.conic_through_points(r)
    assert k.kind == "ellipse"
    assert (k.a, k.b, k.c) == pytest.approx((5.0, 3.0, 4.0), abs=1e-12)
    assert k.eccentricity == pytest.approx(0.8, abs=1e-13)
    assert k.p == pytest.approx(1.8, abs=1e-12)
    assert np.linalg.norm(k.centre - to_space(0, 0)) <= 1e-12
    assert np.linalg.norm(k.focus - to_space(4, 0)) <= 1e-12
    printed(math.degrees(k.theta15), 167.319617, 6)
    s = k.steps(steps=4, omega=0.5)
    printed(s.timing["time"], 5.840556, 6)
    printed(
        s.points[1:4],
        [[104.840316, 200.451271, 300.601695], [104.182641, 200.986263, 301.315017], [102.048748, 201.641957, 302.189275]],
        6,
    )
    assert s.timing["speed_variation"] > 0  # equal focal-angle steps do not keep the feed
    assert k.as_dict()["kind"] == "ellipse"


def test_conic_reference_parabola_and_hyperbola():
    k = kontur.conic_through_points(
        [(96, 202.4, 303.2), (98, 200.6, 300.8), (100, 200, 300), (102, 200.6, 300.8), (106, 205.4, 307.2)]
    )
    assert k.kind == "parabola" and k.eccentricity == 1.0
    assert k.p == pytest.approx(2.0, abs=1e-12)
    printed(math.degrees(k.theta15), 270.0, 9)

    def s(x):
        return 0.5 * x * math.sqrt(1 + x * x / 4) + math.asinh(x / 2)

    assert k.length == pytest.approx(s(6) - s(-4), rel=1e-12)
    h = kontur.conic_through_points(
        [(108.5, 196.625, 295.5), (105, 198.65, 298.2), (104, 200, 300), (105, 201.35, 301.8), (108.5, 203.375, 304.5)]
    )
    assert h.kind == "hyperbola"
    assert (h.a, h.b, h.c, h.eccentricity, h.p) == pytest.approx((4.0, 3.0, 5.0, 1.25, 2.25), abs=1e-12)
    printed(math.degrees(h.theta15), 243.781584, 6)
    printed(h.steps(steps=4, omega=0.5).timing["time"], 8.509583, 6)
    f = h.steps(feed=1200.0, period=0.001)
    assert np.allclose(np.diff(f.s)[:-1], 0.02, atol=1e-12)
    assert np.linalg.norm(f.points[-1] - [108.5, 203.375, 304.5]) == 0.0


def test_conic_rules():
    with pytest.raises(kontur.InputError) as e:
        kontur.conic_through_points([(0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 1, 0), (4, 3, 0)])
    assert e.value.rule == "points-collinear"
    with pytest.raises(kontur.InputError) as e:
        kontur.conic_through_points([(5, 0, 0), (4, 1.8, 0), (3, 2.4, 0), (0, 3, 1), (-4, 1.8, 0)])
    assert e.value.rule == "points-not-coplanar"
    with pytest.raises(kontur.InputError) as e:
        kontur.conic_through_points([(0, 0, 0), (1, 1, 0), (2, 0, 0)])
    assert e.value.rule == "points-count"


def test_arc_evaluate_follows_the_steps_and_refuses_outside():
    c = kontur.circle_through_points([110, 100, 50], [100, 110, 50], [90, 100, 50])
    s = c.steps(steps=8, time=1.0)
    assert np.allclose(c.evaluate(s.u), s.points, atol=1e-12)
    assert c.evaluate(0.5).shape == (3,)
    with pytest.raises(kontur.InputError) as e:
        c.evaluate(1.5)
    assert e.value.rule == "parameter-range"
