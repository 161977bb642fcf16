"""NurbsCurve and read_curve: the seed's reference numbers (the C++ tests' tests/test_length.cpp),
vectorised evaluation against the scalar one and finite differences, u(s), span polynomials and
forward differences against evaluation, and the rules a curve must follow."""

import math

import numpy as np
import pytest

import kontur

SEED_TRUE_LENGTH = {1: 249.463109910705, 2: 252.584228618995}
# The seed's Simpson tables (methods.md), n = 2, 4, ..., 64, printed to 3 decimals.
SEED_SIMPSON_TABLE = {
    1: [286.002, 254.160, 248.737, 249.477, 249.463, 249.463],
    2: [371.378, 252.227, 253.549, 252.185, 252.599, 252.584],
}


def seed_curve(root, which):
    return kontur.read_curve(root / "examples" / "curves" / f"seed_example{which}.json")


def random_curve(rng, degree=3, n=9, rational=True, dim=3):
    inner = np.sort(rng.uniform(0.0, 1.0, n - degree - 1))
    knots = np.concatenate([np.zeros(degree + 1), inner, np.ones(degree + 1)])
    points = rng.uniform(-50.0, 50.0, (n, dim))
    weights = rng.uniform(0.3, 3.0, n) if rational else None
    return kontur.NurbsCurve(degree=degree, knots=knots, points=points, weights=weights)


def test_version_is_the_commands(command):
    assert kontur.__version__ in command("--version").stdout


@pytest.mark.parametrize("which", [1, 2])
def test_seed_lengths(root, which):
    c = seed_curve(root, which)
    assert c.length() == pytest.approx(SEED_TRUE_LENGTH[which], rel=1e-12)
    assert c.length(tolerance=1e-6) == pytest.approx(SEED_TRUE_LENGTH[which], rel=1e-6)


@pytest.mark.parametrize("which", [1, 2])
def test_seed_simpson_table(root, which):
    r = seed_curve(root, which).length_simpson("whole_curve", tolerance=1e-12)
    printed = SEED_SIMPSON_TABLE[which]
    assert len(r["history"]) >= len(printed)
    for i, value in enumerate(printed):
        n, l_n = r["history"][i]
        assert n == 2 << i
        assert abs(l_n - value) <= 0.0005 + 1e-9
    assert r["converged"]
    assert r["length"] == pytest.approx(SEED_TRUE_LENGTH[which], rel=1e-9)
    per_span = seed_curve(root, which).length_simpson("per_span", tolerance=1e-12)
    assert per_span["history"] == []
    assert per_span["length"] == pytest.approx(SEED_TRUE_LENGTH[which], rel=1e-10)


def test_evaluate_vectorised_equals_scalar_and_shapes():
    rng = np.random.default_rng(7)
    for dim in (2, 3):
        c = random_curve(rng, dim=dim)
        u = np.linspace(c.u_min, c.u_max, 101)
        pts = c.evaluate(u)
        assert pts.shape == (101, dim)
        for i in (0, 17, 50, 100):
            assert np.array_equal(c.evaluate(u[i]), pts[i])
        d = c.evaluate(u.reshape(101, 1), derivatives=3)
        assert d.shape == (101, 1, 4, dim)
        assert np.array_equal(d[:, 0, 0, :], pts)
        assert c.evaluate(0.5).shape == (dim,)
        assert c.evaluate(0.5, derivatives=2).shape == (3, dim)
        assert np.array_equal(c(u), pts)


def test_derivatives_match_finite_differences():
    rng = np.random.default_rng(11)
    c = random_curve(rng, degree=4, n=10)
    inner = set(np.round(c.breakpoints, 12))
    for u in rng.uniform(0.05, 0.95, 40):
        if min(abs(u - b) for b in inner) < 1e-4:
            continue
        h = 1e-6
        d = c.evaluate(u, derivatives=3)
        for k in (1, 2, 3):
            fd = (c.evaluate(u + h, derivatives=3)[k - 1] - c.evaluate(u - h, derivatives=3)[k - 1]) / (2 * h)
            scale = max(1.0, np.abs(d[k]).max())
            assert np.abs(d[k] - fd).max() <= 1e-5 * scale


def test_evaluate_refuses_parameters_outside_the_range():
    c = random_curve(np.random.default_rng(1))
    with pytest.raises(kontur.InputError) as e:
        c.evaluate([0.0, 1.5])
    assert e.value.rule == "parameter-range"
    assert "u[1] = 1.5" in str(e.value)
    with pytest.raises(ValueError):
        c.evaluate(float("nan"))
    with pytest.raises(ValueError):
        c.evaluate(0.5, derivatives=4)


def test_arc_length_inverse():
    rng = np.random.default_rng(3)
    c = random_curve(rng)
    L = c.length()
    s = np.linspace(0.0, L, 257)
    u = c.u_of_s(s)
    assert u[0] == c.u_min and u[-1] == pytest.approx(c.u_max, abs=1e-13)
    assert np.all(np.diff(u) > 0)
    assert np.abs(c.s_of_u(u) - s).max() <= 1e-12 * L
    # The inverse against the independent length of the piece [u_min, u]: the polyline of the
    # points converges to it from below.
    uu = np.linspace(c.u_min, u[100], 200001)
    chord = np.linalg.norm(np.diff(c.evaluate(uu), axis=0), axis=1).sum()
    assert chord == pytest.approx(s[100], rel=1e-8)
    assert isinstance(c.u_of_s(1.0), float)
    with pytest.raises(kontur.InputError):
        c.u_of_s(L * 1.01)


def test_span_polynomials_reproduce_the_curve():
    rng = np.random.default_rng(5)
    for rational in (False, True):
        c = random_curve(rng, rational=rational)
        spans = c.span_polynomials()
        assert len(spans) == len(c.breakpoints) - 1
        for sp in spans:
            assert sp["coefficients"].shape == (4, c.degree + 1)
            for u in np.linspace(sp["u_start"], sp["u_end"], 7)[:-1]:
                t = u - sp["u_start"]
                h = np.array([np.polyval(sp["coefficients"][a][::-1], t) for a in range(4)])
                assert np.allclose(h[:3] / h[3], c.evaluate(u), rtol=0, atol=1e-10)
        g = c.span_polynomials(global_parameter=True)
        u = 0.5 * (g[1]["u_start"] + g[1]["u_end"])
        h = np.array([np.polyval(g[1]["coefficients"][a][::-1], u) for a in range(4)])
        assert np.allclose(h[:3] / h[3], c.evaluate(u), atol=1e-8)


def test_forward_differences_follow_the_curve(root):
    c = seed_curve(root, 1)
    for compensated in (False, True):
        fd = c.forward_differences(0.001, compensated=compensated)
        assert len(fd["u"]) == 1001
        assert np.allclose(fd["u"], c.u_min + 0.001 * np.arange(1001), atol=1e-15)
        err = np.abs(fd["points"] - c.evaluate(fd["u"])).max()
        assert err <= (1e-12 if compensated else 1e-9)
        assert fd["span"][0] == 0 and fd["span"][-1] == len(c.breakpoints) - 2
    with pytest.raises(kontur.InputError) as e:
        c.forward_differences(0.0)
    assert e.value.rule == "step-positive"


@pytest.mark.parametrize(
    "kwargs, rule",
    [
        (dict(degree=3, knots=[0, 0, 0, 0, 1, 1, 1], points=[[0, 0], [1, 1], [2, 0], [3, 1]]), "knot-count"),
        (dict(degree=2, knots=[0, 0, 0, 1, 0.5, 1], points=[[0, 0], [1, 1], [2, 0]]), None),
        (dict(degree=1, knots=[0, 0, 1, 1], points=[[0, 0], [1, 1]], weights=[1, -1]), None),
        (dict(degree=1, knots=[0, 0, 1, 1], points=[[0, 0, 0, 0], [1, 1, 1, 1]]), None),
    ],
)
def test_broken_rules_raise_input_error(kwargs, rule):
    with pytest.raises(kontur.InputError) as e:
        kontur.NurbsCurve(**kwargs)
    assert isinstance(e.value, ValueError)
    if rule:
        assert e.value.rule == rule
        assert "knot" in str(e.value)


def test_read_curve_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"degree": 2, "knots": [0, 0, 0, 1, 1], "points": [[0, 0], [1, 1], [2, 0]]}')
    with pytest.raises(kontur.InputError) as e:
        kontur.read_curve(bad)
    assert str(bad) in str(e.value)
    with pytest.raises(kontur.InputError) as e:
        kontur.read_curve(tmp_path / "missing.json")
    assert "missing.json" in str(e.value)


def test_two_dimensional_curve_file(root):
    c = seed_curve(root, 1)
    assert c.points.shape[1] == c.dimension
    assert c.evaluate(c.u_max).shape == (c.dimension,)
    assert math.isfinite(c.length())


@pytest.mark.parametrize("which", [1, 2])
def test_seed_004_feed_fluctuation(root, which):
    c = seed_curve(root, which)
    feed, period = 6000.0, 0.001  # 0.1 mm per cycle, as tests/test_interpolation.cpp
    t1 = c.feed_fluctuation(feed, period, "taylor1")
    t2 = c.feed_fluctuation(feed, period, "taylor2")
    ex = c.feed_fluctuation(feed, period, "exact")
    assert t1["max_relative"] > 1e-4
    assert t2["max_relative"] < t1["max_relative"] / 10
    assert ex["max_relative"] < 1e-9 and ex["cycles"] > 2000
    steps = c.interpolate(feed, period)
    arcs = np.diff(steps["s"])
    assert np.allclose(arcs[:-1], 0.1, rtol=1e-9)
    assert np.array_equal(steps["points"][-1], c.evaluate(c.u_max))
    assert np.allclose(steps["points"], c.evaluate(steps["u"]))
    with pytest.raises(kontur.InputError) as e:
        c.interpolate(0.0)
    assert e.value.rule == "feed-positive"
    with pytest.raises(kontur.InputError):
        c.feed_fluctuation(6000.0, 0.001, "taylor3")
