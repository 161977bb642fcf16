// Seed 002's lower level: forward differences reproduce the seed's initial differences, follow
// the curve across span changes, and drift less than 1e-9 of the curve's extent in 10^6 steps.
#include <gtest/gtest.h>
#include <kontur/interpolate/forward_difference.hpp>
#include <kontur/geometry/nurbs.hpp>

#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace kontur {
namespace {

NurbsData seed_example1() { return testing::seed_example(1); }

TEST(ForwardDifference, SeedInitialDifferencesAtN0AndN10) {
  const NurbsCurve curve(seed_example1());
  const SpanPolynomialCurve spans(curve);
  // Upper level: the seed's x polynomials in the global u, stepped with h = 0.05 from u = 0
  // (X(n) = -0.02n^3 + 0.9n^2 - 100) and from u = 0.5, n = 10 (X(n) = -0.09n^3 + 3n^2 - 21n - 30).
  const PolyCoeffs x1 = spans.spans()[0].coefficients(0, 0.0);
  const PolyCoeffs d0 = initial_differences(x1, 3, 0.0, 0.05);
  EXPECT_NEAR(d0[0], -100, 1e-12);
  EXPECT_NEAR(d0[1], 0.88, 1e-12);
  EXPECT_NEAR(d0[2], 1.68, 1e-12);
  EXPECT_NEAR(d0[3], -0.12, 1e-12);
  const PolyCoeffs x2 = spans.spans()[1].coefficients(0, 0.0);
  const PolyCoeffs d10 = initial_differences(x2, 3, 0.5, 0.05);
  EXPECT_NEAR(d10[0], -30, 1e-12);
  EXPECT_NEAR(d10[1], 12.21, 1e-12);
  EXPECT_NEAR(d10[2], 0.06, 1e-12);
  EXPECT_NEAR(d10[3], -0.54, 1e-12);
  // The seed's D1 formula (corrected): D1(n) = a(3n^2 + 3n + 1) + b(2n + 1) + c with
  // a = A h^3, b = B h^2, c = C h; on span 2 at n = 10.
  const double h = 0.05, a = x2[3] * h * h * h, b = x2[2] * h * h, c = x2[1] * h;
  EXPECT_NEAR(a * (3 * 100 + 30 + 1) + b * 21 + c, 12.21, 1e-12);

  // Lower level: the stepper reaches n = 10 and re-anchors there on span 2 with the same values.
  ForwardDifferenceStepper fd(spans, 0.05);
  EXPECT_NEAR(fd.differences(0)[1], 0.88, 1e-12);
  for (int n = 0; n < 10; ++n) ASSERT_TRUE(fd.step());
  EXPECT_EQ(fd.span(), 1u);
  EXPECT_NEAR(fd.differences(0)[0], -30, 1e-12);
  EXPECT_NEAR(fd.differences(0)[1], 12.21, 1e-12);
  EXPECT_NEAR(fd.differences(0)[2], 0.06, 1e-12);
  EXPECT_NEAR(fd.differences(0)[3], -0.54, 1e-12);
  EXPECT_EQ(fd.cycles(), 20);
}

// Every step of the stepper equals direct evaluation, on random curves (rational ones in
// homogeneous coordinates), with steps that do not divide the spans.
TEST(ForwardDifference, FollowsTheCurveAcrossSpansOnRandomCurves) {
  const auto seed = testing::test_seed();
  const auto count = testing::test_count(100);
  for (std::uint64_t i = 0; i < count; ++i) {
    const NurbsCurve curve(testing::random_nurbs(seed, i, {.max_degree = 5, .max_points = 30}));
    const SpanPolynomialCurve spans(curve);
    const double h = (curve.u_max() - curve.u_min()) / (997.0 + static_cast<double>(i % 13));
    for (const Summation sum : {Summation::plain, Summation::compensated}) {
      ForwardDifferenceStepper fd(spans, h, sum);
      do {
        const Vec3 direct = curve.point(fd.u());
        ASSERT_LE((fd.point() - direct).norm(), 1e-9 * curve.extent())
            << testing::describe_case(seed, i) << " n=" << fd.n() << " u=" << fd.u();
      } while (fd.step());
      EXPECT_EQ(fd.n(), fd.cycles());
      // The last cycle is within one step of the end (up to the rounding of u_min + n h).
      EXPECT_LE(curve.u_max() - fd.u(), h + 16 * std::numeric_limits<double>::epsilon() * std::abs(curve.u_max()));
    }
  }
}

// Drift: 10^6 steps along the seed curve and along random single-span curves (no re-anchoring
// helps there) stay within 1e-9 of the extent of direct evaluation; measured for both summations.
TEST(ForwardDifference, DriftAfterAMillionStepsBelow1e9OfExtent) {
  std::vector<NurbsData> curves = {seed_example1()};
  const auto seed = testing::test_seed();
  for (std::uint64_t i = 0; i < 4; ++i) {
    // Bezier (one span) of degree 3..7, non-rational.
    testing::RandomCurveOptions o;
    o.min_degree = 3 + static_cast<int>(i);
    o.max_degree = o.min_degree;
    o.min_points = o.max_points = o.min_degree + 1;
    o.rational = false;
    curves.push_back(testing::random_nurbs(seed, 500 + i, o));
  }
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const NurbsCurve curve(curves[c]);
    const SpanPolynomialCurve spans(curve);
    const double h = (curve.u_max() - curve.u_min()) / 1e6;
    for (const Summation sum : {Summation::plain, Summation::compensated}) {
      ForwardDifferenceStepper fd(spans, h, sum);
      double worst = 0.0;
      long steps = 0;
      while (fd.step()) {
        ++steps;
        if (steps % 997 == 0 || steps >= 999990) worst = std::max(worst, (fd.point() - curve.point(fd.u())).norm());
      }
      EXPECT_GE(steps, 999999);
      const double relative = worst / curve.extent();
      EXPECT_LT(relative, tolerances::forward_difference_drift_relative)
          << "curve " << c << (sum == Summation::plain ? " plain" : " compensated");
      RecordProperty("drift_curve" + std::to_string(c) + (sum == Summation::plain ? "_plain" : "_compensated"),
                     std::to_string(relative));
      std::printf("drift curve %zu (degree %d) %s: %.3e of extent after %ld steps\n", c, curve.degree(),
                  sum == Summation::plain ? "plain      " : "compensated", relative, steps);
    }
  }
}

}  // namespace
}  // namespace kontur
