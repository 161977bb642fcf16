// The jerk-limited velocity profile of one move: closed-form durations, limits, continuity and an
// exact end over seeded random inputs.
#include <gtest/gtest.h>
#include <kontur/plan/scurve.hpp>

#include "support/random_curves.hpp"

#include <cmath>
#include <random>

namespace kontur::plan {
namespace {

TEST(Scurve, RestToRestDurationMatchesTheClosedForm) {
  // Speed and acceleration limits both reached: T = h / v + v / a + a / j.
  const PathLimits l{50.0, 500.0, 10000.0};
  const ScurveProfile p = plan_scurve(100.0, 0.0, 0.0, l);
  EXPECT_NEAR(p.duration(), 100.0 / 50 + 50.0 / 500 + 500.0 / 10000, 1e-12);
  EXPECT_DOUBLE_EQ(p.peak_velocity(), 50.0);
  // Short move, no limit reached: vp = j T^2 / 4 ... the distance of two triangles: h = 2 vp tj.
  const ScurveProfile q = plan_scurve(0.01, 0.0, 0.0, l);
  const double tj = std::cbrt(0.01 / (2 * 10000.0));  // h = 2 j tj^3
  EXPECT_NEAR(q.duration(), 4 * tj, 1e-9);
  EXPECT_NEAR(q.sample(q.duration()).s, 0.01, 1e-15);
}

TEST(Scurve, VelocityChangeFormulas) {
  // Below a^2 / j: a triangle of duration 2 sqrt(dv / j).
  EXPECT_NEAR(velocity_change_time(10, 10.5, 1000, 1e6), 2 * std::sqrt(0.5 / 1e6), 1e-15);
  EXPECT_NEAR(velocity_change_time(10, 20, 1000, 1e6), 0.001 + 10.0 / 1000, 1e-15);
  // Above: tj = a / j, T = tj + dv / a.
  EXPECT_NEAR(velocity_change_time(0, 100, 500, 1e4), 0.05 + 0.2, 1e-15);
  EXPECT_NEAR(velocity_change_distance(0, 100, 500, 1e4), 50 * 0.25, 1e-12);
  // reachable_velocity inverts the distance.
  const PathLimits l{200.0, 500.0, 1e4};
  const double v = reachable_velocity(5.0, 3.0, l);
  EXPECT_NEAR(velocity_change_distance(5.0, v, 500, 1e4), 3.0, 1e-12);
  EXPECT_EQ(reachable_velocity(5.0, 1e6, l), 200.0);
}

TEST(Scurve, LimitsContinuityAndExactEndOnRandomMoves) {
  const auto seed = testing::test_seed();
  const auto count = testing::test_count(2000);
  std::mt19937_64 rng(seed ^ 0x5C0u);
  auto logu = [&](double a, double b) { return std::exp(std::uniform_real_distribution<double>(std::log(a), std::log(b))(rng)); };
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (std::uint64_t i = 0; i < count; ++i) {
    const PathLimits l{logu(1, 1000), logu(10, 1e5), logu(100, 1e7)};
    const double h = logu(1e-4, 1e3);
    const double v0 = uni(0, 1) < 0.3 ? 0.0 : uni(0, l.max_velocity);
    // An end speed reachable from v0 both ways within h.
    double v1 = uni(0, 1) < 0.3 ? 0.0 : uni(0, reachable_velocity(v0, h, l));
    if (v1 < v0) v1 = std::max(v1, [&] {
      double lo = 0, hi = v0;  // braking must fit: keep v1 above what braking over h allows
      for (int k = 0; k < 200; ++k) {
        const double m = 0.5 * (lo + hi);
        if (velocity_change_distance(m, v0, l.max_acceleration, l.max_jerk) <= h) hi = m; else lo = m;
      }
      return hi;
    }());
    const ScurveProfile p = plan_scurve(h, v0, v1, l);
    const std::string at = "case " + std::to_string(i) + " h=" + std::to_string(h) + " v0=" + std::to_string(v0) +
                           " v1=" + std::to_string(v1);
    ASSERT_NEAR(p.end_velocity(), v1, 1e-9 * l.max_velocity) << at;
    const double T = p.duration();
    ASSERT_TRUE(std::isfinite(T) && T >= 0.0) << at;
    PathState prev = p.sample(0.0);
    ASSERT_EQ(prev.v, v0) << at;
    const int n = 400;
    for (int k = 1; k <= n; ++k) {
      const PathState q = p.sample(T * k / n);
      ASSERT_GE(q.s, prev.s - 1e-12 * h) << at;  // never backwards
      ASSERT_LE(q.v, l.max_velocity * (1 + 1e-12)) << at;
      ASSERT_LE(std::abs(q.a), l.max_acceleration * (1 + 1e-9)) << at;
      ASSERT_LE(std::abs(q.j), l.max_jerk) << at;
      prev = q;
    }
    // The phases close: just before the end the state tends to (h, v1, 0).
    const double eps_t = T * 1e-12;
    const PathState e = p.sample(T - eps_t);
    ASSERT_NEAR(e.s, h, 1e-9 * h + 1e-12) << at;
    ASSERT_NEAR(e.v, v1, 1e-6 * l.max_velocity) << at;
    ASSERT_NEAR(e.a, 0.0, 2 * l.max_jerk * eps_t + 1e-6 * l.max_acceleration) << at;
    const PathState end = p.sample(T);
    ASSERT_EQ(end.s, h) << at;
  }
}

}  // namespace
}  // namespace kontur::plan
