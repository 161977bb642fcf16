// Unit tangent, curvature and chord (bow-height) error.
#include <gtest/gtest.h>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>

#include <cmath>
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

}  // namespace
}  // namespace kontur
