// NURBS validation (every rule, with its message) and evaluation against OpenCASCADE.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/geometry/nurbs.hpp>

#include "support/occt_oracle.hpp"
#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

#include <cmath>
#include <limits>

namespace kontur {
namespace {

NurbsData cubic() { return testing::seed_example(1); }

void expect_problem(const NurbsData& d, const std::string& rule, const std::string& fragment) {
  const auto p = validate(d);
  ASSERT_TRUE(p.has_value()) << "expected rule " << rule;
  EXPECT_EQ(p->rule, rule) << p->message;
  EXPECT_NE(p->message.find(fragment), std::string::npos) << "message: " << p->message;
  try {
    const NurbsCurve c(d);
    ADD_FAILURE() << "constructor accepted an invalid curve";
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), rule);
  }
}

TEST(NurbsValidation, AcceptsSeedExample) { EXPECT_FALSE(validate(cubic()).has_value()); }

TEST(NurbsValidation, RejectsSeed004InconsistentExample) {
  // methods.md section 3: 5 points, 8 knots, 9 weights.
  NurbsData d = testing::seed_004_inconsistent();
  expect_problem(d, "weight-count", "9 weights given for 5 control points");
  d.weights.resize(5);  // with the weights fixed, the knot count is still wrong
  expect_problem(d, "knot-count", "8 knots given, 9 needed (5 control points + degree 3 + 1)");
}

TEST(NurbsValidation, KnotCount) {
  auto d = cubic();
  d.knots.pop_back();
  expect_problem(d, "knot-count", "8 knots given, 9 needed");
}

TEST(NurbsValidation, KnotsDecreasing) {
  auto d = cubic();
  d.points.push_back({0, 0, 0});
  d.knots = {0, 0, 0, 0, 0.7, 0.5, 1, 1, 1, 1};
  expect_problem(d, "knots-decreasing", "knots[5] = 0.5 is less than knots[4] = 0.7");
}

TEST(NurbsValidation, KnotNotFinite) {
  auto d = cubic();
  d.knots[4] = std::numeric_limits<double>::quiet_NaN();
  expect_problem(d, "knot-not-finite", "knots[4]");
}

TEST(NurbsValidation, EndMultiplicity) {
  auto d = cubic();
  d.knots = {0, 0, 0, 0.1, 0.5, 1, 1, 1, 1};
  expect_problem(d, "end-multiplicity", "the first degree + 1 = 4 knots must be equal");
  d.knots = {0, 0, 0, 0, 0.5, 0.9, 1, 1, 1};
  expect_problem(d, "end-multiplicity", "the last degree + 1 = 4 knots must be equal");
  d.knots = {0, 0, 0, 0, 0, 1, 1, 1, 1};
  expect_problem(d, "end-multiplicity", "repeats an end knot");
}

TEST(NurbsValidation, InnerMultiplicity) {
  NurbsData d;
  d.degree = 2;
  d.points = {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}, {4, 0, 0}, {5, 1, 0}};
  d.knots = {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1};
  expect_problem(d, "inner-multiplicity", "inner knot 0.5 appears 3 times");
  d.knots = {0, 0, 0, 0.3, 0.5, 0.5, 1, 1, 1};
  EXPECT_FALSE(validate(d).has_value());  // multiplicity = degree is allowed (C0 corner)
}

TEST(NurbsValidation, Weights) {
  auto d = cubic();
  d.weights = {1, 1, 0, 1, 1};
  expect_problem(d, "weight-positive", "weights[2] = 0");
  d.weights = {1, 1, -2, 1, 1};
  expect_problem(d, "weight-positive", "weights[2] = -2");
  d.weights = {1, 1, std::numeric_limits<double>::infinity(), 1, 1};
  expect_problem(d, "weight-positive", "weights[2] = inf");
}

TEST(NurbsValidation, DegreeAndPointCount) {
  auto d = cubic();
  d.degree = 0;
  expect_problem(d, "degree-range", "degree 0 is outside the supported range 1..9");
  d.degree = 10;
  expect_problem(d, "degree-range", "degree 10");
  d = cubic();
  d.points.resize(3);
  d.knots = {0, 0, 0, 0, 1, 1, 1};
  expect_problem(d, "too-few-points", "3 control points given; a curve of degree 3 needs at least 4");
}

TEST(NurbsValidation, ZeroLengthParameterRange) {
  auto d = cubic();
  d.knots = {1, 1, 1, 1, 1, 1, 1, 1, 1};
  expect_problem(d, "empty-range", "has zero length");
}

TEST(NurbsValidation, PointNotFinite) {
  auto d = cubic();
  d.points[1].y() = std::numeric_limits<double>::quiet_NaN();
  expect_problem(d, "point-not-finite", "points[1]");
}

TEST(NurbsEvaluation, EndsInterpolateFirstAndLastPoint) {
  const NurbsCurve c(cubic());
  EXPECT_EQ(c.point(0.0), Vec3(-100, -60, 0));
  EXPECT_EQ(c.point(1.0), Vec3(30, 120, 0));
  EXPECT_EQ(c.point(-5.0), c.point(0.0));  // clamped to the range
  EXPECT_EQ(c.find_span(1.0), 4);
  EXPECT_EQ(c.find_span(0.5), 4);
  EXPECT_EQ(c.find_span(0.0), 3);
}

// The independent oracle: OpenCASCADE's Geom_BSplineCurve::D3 on at least 200 seeded random
// NURBS (degree 1-7, 4-60 points, random non-uniform knots with repeats, random weights).
TEST(NurbsEvaluation, AgreesWithOpenCascadeOnRandomCurves) {
  const auto seed = testing::test_seed();
  const auto count = std::max<std::uint64_t>(testing::test_count(200), 200);
  std::mt19937_64 rng(seed + 1);
  double worst = 0.0;
  for (std::uint64_t i = 0; i < count; ++i) {
    const NurbsData d = testing::random_nurbs(seed, i, {.rational = (i % 2 == 0)});
    const NurbsCurve curve(d);
    const auto occ = testing::to_occt(d);
    const double size = curve.extent();
    const double range = curve.u_max() - curve.u_min();
    // Sample the oracle first: the scale of the o-th derivative is the larger of the curve's
    // size / range^o and the largest |C^(o)| the oracle shows on this curve (rational curves
    // with weights 0.2..5 have derivatives far above size / range^o).
    struct Sample {
      double u;
      Vec3 ref[4];
    };
    std::vector<Sample> samples;
    double scale[4] = {size, size / range, size / (range * range), size / (range * range * range)};
    for (int s = 0; s < 25; ++s) {
      double u = curve.u_min() + range * std::uniform_real_distribution<double>(0, 1)(rng);
      if (s == 0) u = curve.u_min();
      if (s == 1) u = curve.u_max();
      if (s == 2) u = d.knots[static_cast<std::size_t>(d.degree + 1)];  // on a knot
      gp_Pnt P;
      gp_Vec V1, V2, V3;
      occ->D3(u, P, V1, V2, V3);
      Sample smp{u, {{P.X(), P.Y(), P.Z()}, {V1.X(), V1.Y(), V1.Z()}, {V2.X(), V2.Y(), V2.Z()}, {V3.X(), V3.Y(), V3.Z()}}};
      for (int o = 0; o <= 3; ++o) scale[o] = std::max(scale[o], smp.ref[o].norm());
      samples.push_back(smp);
    }
    for (const Sample& smp : samples) {
      const Derivatives k = curve.derivatives(smp.u, 3);
      for (int o = 0; o <= 3; ++o) {
        const double err = (k[o] - smp.ref[o]).norm() / scale[o];
        worst = std::max(worst, err);
        ASSERT_LE(err, 1e-12) << testing::describe_case(seed, i) << " degree " << d.degree << " u=" << smp.u
                              << " derivative " << o;
      }
    }
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace
}  // namespace kontur
