// Seed 004's interpolators (methods.md section 3) and Kontur's arc-length-exact one: feed
// fluctuation, the chord-error feed limit, exact steps on a circle.
#include <gtest/gtest.h>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

#include <cmath>
#include <numbers>

namespace kontur {
namespace {

TEST(Interpolation, FluctuationOrderingOnSeedCurves) {
  for (int which : {1, 2}) {
    const NurbsCurve curve(testing::seed_example(which));
    const SpanPolynomialCurve spans(curve);
    const double feed = 6000.0 / 60.0, period = 1e-3;  // 6000 mm/min, 1 ms
    const auto t1 = measure_feed_fluctuation(spans, Interpolator::taylor_first_order, feed, period);
    const auto t2 = measure_feed_fluctuation(spans, Interpolator::taylor_second_order, feed, period);
    const auto ex = measure_feed_fluctuation(spans, Interpolator::arc_length_exact, feed, period);
    EXPECT_GT(t1.max_relative, 1e-4) << "first order has a visible fluctuation";
    EXPECT_LT(t2.max_relative, t1.max_relative / 10);
    EXPECT_LT(ex.max_relative, 1e-9) << "example " << which;
    EXPECT_GT(ex.cycles, 2000);
    // The tool never passes the end: the last setpoint before it is less than one step away.
    EXPECT_LT(ex.final_gap_mm, feed * period * (1 + 1e-9));
  }
}

TEST(Interpolation, ExactModeHoldsTheFeedOnRandomCurves) {
  const auto seed = testing::test_seed();
  const auto count = testing::test_count(20);
  for (std::uint64_t i = 0; i < count; ++i) {
    const NurbsCurve curve(testing::random_nurbs(seed, 3000 + i, {.max_degree = 5, .max_points = 12, .offset_knots = false}));
    const SpanPolynomialCurve spans(curve);
    // A feed giving about 2000 cycles along the curve.
    const double period = 1e-3, feed = length(spans) / (2000 * period);
    const auto ex = measure_feed_fluctuation(spans, Interpolator::arc_length_exact, feed, period);
    EXPECT_LT(ex.max_relative, 1e-6) << testing::describe_case(seed, 3000 + i);
  }
}

TEST(Interpolation, ExactStepsOnACircleHaveTheExactChord) {
  const double R = 30.0;
  const HelixArc arc(CircleFrame{}, R, 1.9 * std::numbers::pi);
  CurveInterpolator ip(arc);
  const double ds = 0.7;
  Vec3 prev = ip.point();
  int steps = 0;
  while (true) {
    ip.advance(ds);
    if (ip.at_end()) break;
    const Vec3 q = ip.point();
    EXPECT_NEAR((q - prev).norm(), 2 * R * std::sin(ds / (2 * R)), 1e-12);
    EXPECT_NEAR(q.norm(), R, 1e-12);
    prev = q;
    ++steps;
  }
  EXPECT_EQ(steps, static_cast<int>(std::floor(R * 1.9 * std::numbers::pi / ds)));
  EXPECT_EQ(ip.u(), 1.0);
}

TEST(Interpolation, ChordLimitedFeed) {
  // v <= (2/T) sqrt(R^2 - (R - delta)^2): R = 10 mm, delta = 1 um, T = 1 ms.
  const double v = chord_limited_feed(10.0, 1e-3, 1e-3);
  EXPECT_NEAR(v, 2.0 / 1e-3 * std::sqrt(100.0 - (10.0 - 1e-3) * (10.0 - 1e-3)), 1e-9);
  EXPECT_TRUE(std::isinf(chord_limited_feed(std::numeric_limits<double>::infinity(), 1e-3, 1e-3)));
}

TEST(Interpolation, NamesAreStable) {
  EXPECT_STREQ(to_string(Interpolator::taylor_first_order), "taylor1");
  EXPECT_STREQ(to_string(Interpolator::taylor_second_order), "taylor2");
  EXPECT_STREQ(to_string(Interpolator::arc_length_exact), "exact");
}

}  // namespace
}  // namespace kontur
