// Unit tangent, curvature and chord (bow-height) error.
#include <gtest/gtest.h>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <vector>
#include <limits>
#include <numbers>

namespace kontur {
namespace {

TEST(Differential, CircleHasCurvatureOneOverRadius) {
  CircleFrame f;
  f.centre = {1, 2, 3};
  const HelixArc arc(f, 25.0, 1.5 * std::numbers::pi);
  for (double u : {0.0, 0.3, 0.77, 1.0}) {
    const Derivatives d = arc.derivatives(u, 3);
    EXPECT_NEAR(curvature(d), 1.0 / 25.0, 1e-15);
    EXPECT_NEAR(unit_tangent(d).norm(), 1.0, 1e-15);
  }
}

TEST(Differential, HelixCurvature) {
  // Helix of radius r and pitch rise per radian c: kappa = r / (r^2 + c^2).
  const double r = 10.0, sweep = 4 * std::numbers::pi, rise = 30.0, c = rise / sweep;
  const HelixArc helix(CircleFrame{}, r, sweep, rise);
  EXPECT_NEAR(curvature(helix.derivatives(0.4, 2)), r / (r * r + c * c), 1e-15);
}

TEST(Differential, RationalQuadraticArcIsExactCircle) {
  // Quarter circle of radius 50 as a rational quadratic (weights 1, sqrt(2)/2, 1).
  NurbsData d;
  d.degree = 2;
  d.knots = {0, 0, 0, 1, 1, 1};
  d.points = {{50, 0, 0}, {50, 50, 0}, {0, 50, 0}};
  d.weights = {1, std::sqrt(0.5), 1};
  const NurbsCurve arc(d);
  for (double u : {0.0, 0.1, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(arc.point(u).norm(), 50.0, 1e-12);
    EXPECT_NEAR(curvature(arc.derivatives(u, 2)), 1.0 / 50.0, 1e-14);
  }
}

TEST(Differential, ChordErrorFormulaAndInverse) {
  // delta = R - sqrt(R^2 - L^2/4)
  EXPECT_NEAR(chord_error(10.0, 2.0), 10.0 - std::sqrt(99.0), 1e-15);
  EXPECT_EQ(chord_error(std::numeric_limits<double>::infinity(), 5.0), 0.0);
  EXPECT_EQ(chord_error(1.0, 5.0), 1.0);  // longer than the diameter
  // Tiny steps: no cancellation (L^2 / 8R to first order).
  EXPECT_NEAR(chord_error(1000.0, 1e-6), 1e-12 / 8000.0, 1e-30);
  // Inverse: the longest chord within the tolerance has exactly that bow height.
  for (double R : {0.5, 10.0, 1e4})
    for (double tol : {1e-6, 1e-3, 0.1}) EXPECT_NEAR(chord_error(R, max_chord_for_error(R, tol)), tol, 1e-12 * R);
  EXPECT_TRUE(std::isinf(max_chord_for_error(std::numeric_limits<double>::infinity(), 1e-3)));
}

TEST(Differential, SampledChordErrorOfAnArcMatchesFormula) {
  const HelixArc arc(CircleFrame{}, 20.0, 0.5);
  const double chord = 2 * 20.0 * std::sin(0.25);
  EXPECT_NEAR(chord_error(arc, 0.0, 1.0, 2001), chord_error(20.0, chord), 1e-6);
  EXPECT_NEAR(chord_error(LineSegment({0, 0, 0}, {1, 1, 1}), 0.0, 1.0), 0.0, 1e-15);
}

TEST(Differential, NonRegularPointGivesZeroNotNaN) {
  Derivatives d;  // C' = 0
  EXPECT_EQ(curvature(d), 0.0);
  EXPECT_EQ(unit_tangent(d), Vec3::Zero());
}

// The plane cubic x = sum ax_i t^i, y = sum ay_i t^i on [0, 1] (monomial coefficients) as span
// polynomials (its Bezier points from the monomials).
std::shared_ptr<SpanPolynomialCurve> plane_cubic(const std::array<double, 4>& ax, const std::array<double, 4>& ay) {
  const auto bezier = [](const std::array<double, 4>& a) {
    return std::array<double, 4>{a[0], a[0] + a[1] / 3.0, a[0] + 2.0 * a[1] / 3.0 + a[2] / 3.0, a[0] + a[1] + a[2] + a[3]};
  };
  const auto bx = bezier(ax), by = bezier(ay);
  NurbsData d;
  d.degree = 3;
  d.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  for (std::size_t i = 0; i < 4; ++i) d.points.emplace_back(bx[i], by[i], 0.0);
  return std::make_shared<SpanPolynomialCurve>(NurbsCurve(d));
}

// stationary_points skips the refinement of a grid minimum of |C'|^2 that Markov's inequality
// shows to be far from zero, on a polynomial curve only: every cusp off the grid is still found,
// on the span polynomials of a cubic and on a piece of them (seeded cusp places t0).
TEST(Differential, StationaryPointsFindsEveryCuspOfAPolynomialCurveOffTheGrid) {
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<double> place(0.02, 0.98), scale(0.1, 100.0);
  for (int trial = 0; trial < 300; ++trial) {
    const double t0 = place(rng), sx = scale(rng), sy = scale(rng);
    // x = sx (t - t0)^3, y = sy (t - t0)^2: |C'| = 0 at t0 only
    const auto spans = plane_cubic({-sx * t0 * t0 * t0, 3.0 * sx * t0 * t0, -3.0 * sx * t0, sx},
                                   {sy * t0 * t0, -2.0 * sy * t0, sy, 0.0});
    ASSERT_EQ(spans->polynomial_degree(), 3);
    const std::vector<double> at = stationary_points(*spans, 1e-6, 64);
    ASSERT_EQ(at.size(), 1u) << "t0 = " << t0;
    EXPECT_NEAR(at[0], t0, 1e-6) << "t0 = " << t0;
    const CurvePiece piece(spans, 0.5 * t0, 0.5 * (1.0 + t0));
    const std::vector<double> in_piece = stationary_points(piece, 1e-6, 64);
    ASSERT_EQ(in_piece.size(), 1u) << "t0 = " << t0;
    EXPECT_NEAR(in_piece[0], t0, 1e-6) << "t0 = " << t0;
  }
  // and a line has none, with nothing to refine
  EXPECT_TRUE(stationary_points(LineSegment(Vec3(0, 0, 0), Vec3(1, 2, 3)), 1e-6, 64).empty());
}

// stationary_points skips its grid on a polynomial curve whose |C'| is bounded away from zero on
// every span (bounds from the derivatives at the spans' middles): seeded near-cusps whose
// smallest |C'| is a tenth of the relative limit are still found, those at ten times it are not,
// on the span polynomials and on a piece of them; and a smoothed run's curve has none.
TEST(Differential, StationaryPointsBoundSkipsOnlyCurvesFarFromAStop) {
  std::mt19937 rng(20261204);
  std::uniform_real_distribution<double> place(0.1, 0.9), scale(0.5, 5.0);
  const double relative = 1e-3;
  for (int trial = 0; trial < 200; ++trial) {
    const double t0 = place(rng), sx = scale(rng), sy = scale(rng);
    for (const double share : {0.1, 10.0}) {
      // x = sx (t - t0)^3 + e t, y = sy (t - t0)^2: |C'| = e at t0, its smallest; its largest
      // (at the end farther from t0, w away) about hypot(3 sx w^2, 2 sy w)
      const double w = std::max(t0, 1.0 - t0);
      const double e = share * relative * std::hypot(3.0 * sx * w * w, 2.0 * sy * w);
      const auto spans = plane_cubic({-sx * t0 * t0 * t0, 3.0 * sx * t0 * t0 + e, -3.0 * sx * t0, sx},
                                     {sy * t0 * t0, -2.0 * sy * t0, sy, 0.0});
      const std::vector<double> at = stationary_points(*spans, relative, 64);
      const CurvePiece piece(spans, 0.5 * t0, 0.5 * (1.0 + t0));
      const std::vector<double> in_piece = stationary_points(piece, relative, 64);
      if (share < 1.0) {
        EXPECT_EQ(at.size(), 1u) << "t0 = " << t0;
        EXPECT_EQ(in_piece.size(), 1u) << "t0 = " << t0;
      } else {
        EXPECT_TRUE(at.empty()) << "t0 = " << t0;
        EXPECT_TRUE(in_piece.empty()) << "t0 = " << t0;
      }
    }
  }
  // a quarter circle of 200 lines smoothed: its curve and every piece of it have none
  std::vector<Vec3> v;
  for (int i = 0; i <= 200; ++i) v.emplace_back(5.0 * std::sin(0.5 * std::numbers::pi * i / 200), 5.0 * std::cos(0.5 * std::numbers::pi * i / 200), 0.0);
  const std::optional<PolylineFit> fit = fit_polyline(v, Vec3(1, 0, 0), Vec3(0, -1, 0), 0.01);
  ASSERT_TRUE(fit.has_value());
  const auto curve = std::make_shared<SpanPolynomialCurve>(fit->curve);
  EXPECT_TRUE(stationary_points(*curve, 1e-6, 64).empty());
  for (std::size_t i = 0; i + 1 < fit->vertex_u.size(); ++i)
    EXPECT_TRUE(stationary_points(CurvePiece(curve, fit->vertex_u[i], fit->vertex_u[i + 1]), 1e-6, 64).empty()) << i;
}

}  // namespace
}  // namespace kontur
