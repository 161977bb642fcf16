// Look-ahead: junction speeds, streaming equals whole-program planning, and path limits from
// geometry and the machine.
#include <gtest/gtest.h>
#include <kontur/helix_arc.hpp>
#include <kontur/interpolation.hpp>
#include <kontur/line_segment.hpp>
#include <kontur/plan/lookahead.hpp>

#include "support/random_curves.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace kontur::plan {
namespace {

MoveConstraint move(double length, double vcap, double junction, double a = 1000, double j = 1e5) {
  return {length, {vcap, a, j}, junction};
}

TEST(Lookahead, LongMovesCruiseThroughTangentJunctions) {
  const std::vector<MoveConstraint> m = {move(100, 50, 1e9), move(100, 50, 1e9), move(100, 50, 0)};
  const auto v = junction_velocities(m);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_EQ(v[1], 50.0);
  EXPECT_EQ(v[2], 50.0);
  EXPECT_EQ(v[3], 0.0);
}

TEST(Lookahead, BrakingStartsEarlyEnoughOverManyShortMoves) {
  // 200 moves of 0.5 mm at up to 100 mm/s, ending at rest: every junction speed can be braked to
  // the next within the move between, and the speed profile is a ramp, not a cliff.
  std::vector<MoveConstraint> m(200, move(0.5, 100, 1e9, 500, 1e4));
  m.back().max_end_velocity = 0.0;
  const auto v = junction_velocities(m);
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double lo = std::min(v[i], v[i + 1]), hi = std::max(v[i], v[i + 1]);
    EXPECT_LE(velocity_change_distance(lo, hi, 500, 1e4), 0.5 * (1 + 1e-9)) << "move " << i;
  }
  EXPECT_GT(v[100], 50.0);                 // cruising in the middle
  EXPECT_LT(v[199], v[190]);               // braking towards the end
  EXPECT_EQ(v[200], 0.0);
}

// Streaming with the bounded window gives exactly the profiles of planning the whole sequence.
TEST(Lookahead, StreamingEqualsWholeProgramPlanning) {
  std::mt19937_64 rng(testing::test_seed());
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<MoveConstraint> m;
    for (int i = 0; i < 300; ++i)
      m.push_back(move(std::exp(uni(std::log(0.01), std::log(20.0))), uni(5, 200),
                       uni(0, 1) < 0.2 ? 0.0 : uni(0, 300), uni(200, 3000), uni(1e4, 1e6)));
    m.back().max_end_velocity = 0.0;
    const auto v = junction_velocities(m);
    Lookahead la;
    std::size_t next = 0, popped = 0;
    while (popped < m.size()) {
      if (la.ready()) {
        const ScurveProfile p = la.pop();
        ASSERT_NEAR(p.start_velocity(), v[popped], 1e-9 * 300) << "trial " << trial << " move " << popped;
        ASSERT_NEAR(p.end_velocity(), v[popped + 1], 1e-9 * 300) << "trial " << trial << " move " << popped;
        ++popped;
      } else if (next < m.size()) {
        la.push(m[next++]);
        if (next == m.size()) la.finish();
      }
      ASSERT_LE(la.size(), m.size());
    }
  }
}

TEST(MoveLimits, LinesAlongAnAxisAndDiagonal) {
  Machine mc = default_machine();  // X Y Z: 200 mm/s, 2000 mm/s^2, 50000 mm/s^3
  const LineSegment x({0, 0, 0}, {100, 0, 0});
  PathLimits l = move_limits({&x, 100.0, 1000.0}, mc);
  EXPECT_DOUBLE_EQ(l.max_velocity, std::min(200.0, mc.max_feed_mm_s));
  EXPECT_DOUBLE_EQ(l.max_acceleration, 2000.0);
  EXPECT_DOUBLE_EQ(l.max_jerk, 50000.0);
  mc.max_feed_mm_s = 1e4;
  const LineSegment diag({0, 0, 0}, {100, 100, 0});
  l = move_limits({&diag, diag.length_mm(), 1e4}, mc);
  EXPECT_NEAR(l.max_velocity, 200.0 * std::sqrt(2.0), 1e-9);  // each axis at its own limit
  EXPECT_NEAR(l.max_acceleration, 2000.0 * std::sqrt(2.0), 1e-9);
  // The feed caps it when lower.
  l = move_limits({&diag, diag.length_mm(), 10.0}, mc);
  EXPECT_DOUBLE_EQ(l.max_velocity, 10.0);
}

TEST(MoveLimits, CircleByCentripetalJerkCurvatureChangeAndChord) {
  Machine mc = default_machine();  // A = 2000 mm/s^2, J = 50000 mm/s^3 on every axis
  mc.max_feed_mm_s = 1e4;
  const double R = 2.0;
  const HelixArc arc(CircleFrame{}, R, 2 * std::numbers::pi);
  const PathLimits l = move_limits({&arc, arc.length_mm(), 1e4}, mc);
  // The curvature vector turns at |dK/ds| = 1/R^2: K' v^3 <= 0.2 J; the centripetal part takes up
  // to 0.9 A; the chord limit.
  const double rate = std::cbrt(tolerances::plan_curvature_rate_jerk_share * 50000.0 * R * R);
  const double centripetal = std::sqrt(0.9 * 2000.0 * R);
  const double chord = chord_limited_feed(R, mc.chord_tolerance_mm, mc.servo_period_s);
  const double exact = std::min({centripetal, rate, chord, 200.0});
  // Sampled bounds are raised by a small share of their range: at most a few per cent slower.
  EXPECT_LE(l.max_velocity, exact * (1 + 1e-12));
  EXPECT_GE(l.max_velocity, exact * 0.97);
  // Whatever the speed, each axis's acceleration |t_i| a + K_i v^2 stays within its limit.
  EXPECT_LE(l.max_acceleration + l.max_velocity * l.max_velocity / R, 2000.0 * (1 + 1e-12));
  EXPECT_GT(l.max_acceleration, 0.0);
  EXPECT_GT(l.max_jerk, 0.0);
}

TEST(MoveLimits, MotionOnAnAxisTheMachineLacksIsRefusedBySpeedZero) {
  Machine mc = default_machine();
  mc.axes.erase(mc.axes.begin() + 1);  // no Y
  const LineSegment y({0, 0, 0}, {0, 10, 0});
  EXPECT_EQ(move_limits({&y, 10.0, 100.0}, mc).max_velocity, 0.0);
}

Derivatives direction(const Vec3& t, const Vec3& curvature_vector = Vec3::Zero()) {
  Derivatives d;
  d[1] = t;
  d[2] = curvature_vector;  // |C'| = 1: C'' across t is the curvature vector
  return d;
}

TEST(JunctionLimit, TangentCornerReversalAndCurvatureJump) {
  const Machine mc = default_machine();  // J = 50000 mm/s^3, T = 1 ms
  EXPECT_TRUE(std::isinf(junction_limit(direction(Vec3::UnitX()), direction(Vec3::UnitX()), mc)));
  EXPECT_NEAR(junction_limit(direction(Vec3::UnitX()), direction(Vec3::UnitY()), mc), 50000.0 * 1e-6, 1e-12);
  EXPECT_NEAR(junction_limit(direction(Vec3::UnitX()), direction(-Vec3::UnitX()), mc), 50000.0 * 1e-6 / 2, 1e-12);
  // Line into a tangent arc of radius 20: v^2 / R <= J T.
  EXPECT_NEAR(junction_limit(direction(Vec3::UnitX()), direction(Vec3::UnitX(), Vec3(0, 1.0 / 20, 0)), mc),
              std::sqrt(50000.0 * 1e-3 * 20), 1e-9);
}

}  // namespace
}  // namespace kontur::plan
