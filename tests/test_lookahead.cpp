// Look-ahead: junction speeds, streaming equals whole-program planning, and path limits from
// geometry and the machine.
#include <gtest/gtest.h>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/plan/lookahead.hpp>

#include "support/random_curves.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace kontur::plan {
namespace {

MoveConstraint move(double length, double vcap, double junction, double a = 1000, double j = 1e5) {
  return {length, {vcap, a, j}, junction, {}};
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
        const auto p = la.pop();
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

// Streams `m` through a Lookahead as MotionPlanner does (push, then pop while ready) and checks
// every profile against junction_velocities of the whole sequence; returns the largest window.
std::size_t stream_and_compare(const std::vector<MoveConstraint>& m, Lookahead& la) {
  const auto v = junction_velocities(m);
  std::size_t popped = 0, largest = 0;
  auto release = [&] {
    while (la.ready()) {
      const auto p = la.pop();
      EXPECT_NEAR(p.start_velocity(), v[popped], 1e-9 * 300) << "move " << popped;
      EXPECT_NEAR(p.end_velocity(), v[popped + 1], 1e-9 * 300) << "move " << popped;
      ++popped;
    }
  };
  for (const MoveConstraint& c : m) {
    la.push(c);
    largest = std::max(largest, la.size());
    release();
  }
  la.finish();
  release();
  EXPECT_EQ(popped, m.size());
  EXPECT_EQ(la.size(), 0u);
  return largest;
}

// Thousands of tiny moves (as linuxcnc-tp/performance/short_segments_0.001): braking spans
// hundreds of them, so the window is long; the streaming plan still equals the whole plan, and
// the look-ahead makes a bounded number of braking evaluations per move, not one per move of the
// window (the cost was O(moves x window)).
TEST(Lookahead, ManyTinyMovesStreamEqualsWholePlanWithBoundedEvaluationsPerPush) {
  std::vector<MoveConstraint> m;
  for (int i = 0; i < 3000; ++i) {
    // 0.1 mm moves at up to 50 mm/s, a slower stretch and a stop in between.
    const double cap = i >= 1200 && i < 1300 ? 20.0 : 50.0;
    m.push_back(move(0.1, cap, i == 2000 ? 0.0 : 1e9, 1000, 1e5));
  }
  m.back().max_end_velocity = 0.0;
  Lookahead la;
  const std::size_t largest = stream_and_compare(m, la);
  EXPECT_GT(largest, 100u);  // the window does span many moves
  const double per_move = static_cast<double>(la.braking_evaluations()) / static_cast<double>(m.size());
  EXPECT_LT(per_move, 30.0) << "largest window " << largest;
}

// The look-ahead as it was before its passes were cached: both backward passes over the whole
// window for every ready(), and a full re-plan for every pop(). The cached one must give exactly
// the same profiles.
class ReplanningLookahead {
public:
  std::vector<MoveConstraint> window;
  bool finished = false;

  bool ready() const {
    if (window.empty()) return false;
    if (finished) return true;
    return junction1(0.0) >= junction1(window.back().limits.max_velocity);
  }
  trajectory::PathProfile pop() {
    const std::size_t n = window.size();
    std::vector<double> v(n + 1, 0.0);
    v[0] = v_start_;
    for (std::size_t i = 1; i < n; ++i) v[i] = cap(i);
    for (std::size_t i = n; i-- > 1;) v[i] = std::min(v[i], braking_velocity(v[i + 1], window[i]));
    for (std::size_t i = 0; i < n; ++i) v[i + 1] = std::min(v[i + 1], reachable_velocity(v[i], window[i]));
    trajectory::PathProfile p = move_profile(window[0], v_start_, v[1]);
    v_start_ = p.end_velocity();
    window.erase(window.begin());
    return p;
  }

private:
  double cap(std::size_t i) const {
    return std::min({window[i - 1].max_end_velocity, window[i - 1].limits.max_velocity, window[i].limits.max_velocity});
  }
  double junction1(double v_end) const {
    double v = v_end;
    for (std::size_t i = window.size(); i-- > 1;)
      v = std::min(cap(i), braking_velocity(v, window[i]));
    return v;
  }
  double v_start_ = 0.0;
};

TEST(Lookahead, SameProfilesAsReplanningTheWindowWhenTheLastMoveIsLoweredAfterPush) {
  // MotionPlanner lowers the last move's end speed and limits (through back()) when the next one
  // arrives; the cached passes must see it, and give bit for bit the profiles of re-planning the
  // whole window each time.
  std::mt19937_64 rng(testing::test_seed());
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int trial = 0; trial < 10; ++trial) {
    Lookahead la;
    ReplanningLookahead ref;
    std::vector<trajectory::PathProfile> got, want;
    for (int i = 0; i < 600; ++i) {
      // Mostly tiny moves, so that windows get long and readiness tests are deferred.
      const double length = uni(0, 1) < 0.8 ? uni(0.01, 0.05) : std::exp(uni(std::log(0.05), std::log(5.0)));
      const MoveConstraint c = move(length, uni(0, 1) < 0.7 ? 60.0 : uni(5, 200), 1e9, uni(200, 3000), uni(1e4, 1e6));
      if (la.size() > 0) {
        MoveConstraint& last = la.back();
        last.max_end_velocity = std::min(last.max_end_velocity, uni(0, 1) < 0.05 ? 0.0 : uni(0, 300));
        if (uni(0, 1) < 0.3) last.limits.max_acceleration *= uni(0.3, 1.0);
        if (uni(0, 1) < 0.3) last.limits.max_jerk *= uni(0.3, 1.0);
        ref.window.back() = last;
      }
      la.push(c);
      ref.window.push_back(c);
      while (la.ready()) got.push_back(la.pop());
      while (ref.ready()) want.push_back(ref.pop());
    }
    la.limit_last_end_velocity(0.0);
    ref.window.back().max_end_velocity = 0.0;
    la.finish();
    ref.finished = true;
    while (la.ready()) got.push_back(la.pop());
    while (ref.ready()) want.push_back(ref.pop());
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].start_velocity(), want[k].start_velocity()) << "trial " << trial << " move " << k;
      ASSERT_EQ(got[k].end_velocity(), want[k].end_velocity()) << "trial " << trial << " move " << k;
      ASSERT_EQ(got[k].duration(), want[k].duration()) << "trial " << trial << " move " << k;
    }
  }
}

// The motion planner asks after every move whether the oldest chain is final, but pushes only
// closed chains: asking again of a window that has not changed costs no braking evaluation (a
// circle of 10,000 lines in 40 chains cost 0.48 s of braking searches under speed bands).
TEST(Lookahead, AskingAgainOfAnUnchangedWindowCostsNoEvaluation) {
  Lookahead la;
  for (int i = 0; i < 50; ++i) la.push(move(0.02, 100, 1e9, 500, 1e4));  // braking needs more than the window
  ASSERT_FALSE(la.ready());
  const std::size_t evaluations = la.braking_evaluations();
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(la.ready());
  EXPECT_EQ(la.braking_evaluations(), evaluations);
  la.limit_last_end_velocity(0.0);  // a change: asked anew
  (void)la.ready();
  EXPECT_GT(la.braking_evaluations(), evaluations);
}

// A curved move's speed bands: up to `boost` times its acceleration at half its cap, falling to
// its own at the cap (as constraints.hpp's acceleration_bands gives them on a curve).
MoveConstraint with_bands(MoveConstraint m, double boost, double jerk_share) {
  const double tops[] = {0.5, 0.7, 0.85, 0.95, 1.0};
  m.bands.n = 5;
  m.bands.max_jerk = jerk_share * m.limits.max_jerk;
  for (std::size_t k = 0; k < 5; ++k) {
    m.bands.top_mm_s[k] = k + 1 < 5 ? tops[k] * m.limits.max_velocity : m.limits.max_velocity;
    m.bands.acceleration[k] = m.limits.max_acceleration * (1.0 + (boost - 1.0) * (1.0 - tops[k]) / 0.5);
  }
  return m;
}

TEST(Lookahead, BandsLetACurvedMoveSpeedUpAndBrakeHarderBelowItsCap) {
  // 20 moves of 2 mm at up to 150 mm/s, whose acceleration at the cap is 100 mm/s^2 but 700 at
  // half of it: the junction speeds rise and fall faster than the S-curve at 100 allows, each by
  // exactly what the bands allow.
  std::vector<MoveConstraint> plain(20, move(2.0, 150, 1e9, 100, 1e5)), banded;
  plain.back().max_end_velocity = 0.0;
  for (const MoveConstraint& m : plain) banded.push_back(with_bands(m, 7.0, 1.0));
  const auto v_plain = junction_velocities(plain), v = junction_velocities(banded);
  EXPECT_GT(v[1], 1.5 * v_plain[1]);
  EXPECT_GT(v[19], 1.5 * v_plain[19]);
  EXPECT_NEAR(v[1], banded_reachable_velocity(0.0, 2.0, banded[0].bands), 1e-9);
  EXPECT_NEAR(v[19], banded_braking_velocity(0.0, 2.0, banded[19].bands), 1e-9);
  for (std::size_t i = 0; i < banded.size(); ++i) {
    const double lo = std::min(v[i], v[i + 1]), hi = std::max(v[i], v[i + 1]);
    EXPECT_LE(banded_change_distance(lo, hi, banded[i].bands), 2.0 * (1 + 1e-9)) << "move " << i;
  }
}

// Streaming moves with and without bands gives the junction speeds of planning the whole
// sequence, and every move's profile stays within its limits (the S-curve) or its bands.
TEST(Lookahead, BandedMovesStreamAsTheWholeSequenceIsPlannedAndKeepTheirBands) {
  std::mt19937_64 rng(testing::test_seed());
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<MoveConstraint> m;
    for (int i = 0; i < 300; ++i) {
      MoveConstraint c = move(std::exp(uni(std::log(0.01), std::log(20.0))), uni(5, 200),
                              uni(0, 1) < 0.2 ? 0.0 : uni(0, 300), uni(50, 3000), uni(1e4, 1e6));
      m.push_back(uni(0, 1) < 0.6 ? with_bands(c, uni(1.5, 8.0), uni(0.6, 1.0)) : c);
    }
    m.back().max_end_velocity = 0.0;
    const auto v = junction_velocities(m);
    Lookahead la;
    std::size_t popped = 0;
    const auto take = [&] {
      const trajectory::PathProfile p = la.pop();
      const MoveConstraint& c = m[popped];
      ASSERT_NEAR(p.start_velocity(), v[popped], 1e-9 * 300) << "trial " << trial << " move " << popped;
      ASSERT_NEAR(p.end_velocity(), v[popped + 1], 1e-9 * 300) << "trial " << trial << " move " << popped;
      ASSERT_NEAR(p.distance(), c.length_mm, 1e-9 * c.length_mm) << "trial " << trial << " move " << popped;
      bool in_limits = true, in_bands = c.bands.n > 0;
      for (int k = 0; k <= 400; ++k) {
        const trajectory::PathState x = p.sample(p.duration() * k / 400.0);
        in_limits = in_limits && std::abs(x.a) <= c.limits.max_acceleration * (1 + 1e-9) &&
                    std::abs(x.j) <= c.limits.max_jerk * (1 + 1e-9) && x.v <= c.limits.max_velocity * (1 + 1e-9);
        in_bands = in_bands && std::abs(x.a) <= c.bands.at(x.v * (1 - 1e-9)) * (1 + 1e-9) &&
                   std::abs(x.j) <= c.bands.max_jerk * (1 + 1e-9) && x.v <= c.limits.max_velocity * (1 + 1e-9);
      }
      EXPECT_TRUE(in_limits || in_bands) << "trial " << trial << " move " << popped;
      ++popped;
    };
    for (const MoveConstraint& c : m) {
      la.push(c);
      while (la.ready()) take();
    }
    la.finish();
    while (la.ready()) take();
    ASSERT_EQ(popped, m.size());
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
  // The curvature vector turns at |dK/ds| = 1/R^2: K' v^3 <= r J, r one of the curvature-change
  // shares; the centripetal part takes c A, c one of the centripetal shares; the chord limit. The
  // cap is the exact one of some pair (c, r): sampled bounds are raised by a small share of their
  // range, at most a few per cent slower.
  const double chord = chord_limited_feed(R, mc.chord_tolerance_mm, mc.servo_period_s);
  bool matches = false;
  for (const double c : tolerances::plan_centripetal_shares)
    for (const double r : tolerances::plan_curvature_rate_jerk_shares) {
      const double exact = std::min({std::sqrt(c * 2000.0 * R), std::cbrt(r * 50000.0 * R * R), chord, 200.0});
      matches = matches || (l.max_velocity <= exact * (1 + 1e-12) && l.max_velocity >= exact * 0.97);
    }
  EXPECT_TRUE(matches) << l.max_velocity;
  // The largest share of the curvature change bounds it from above.
  EXPECT_LE(l.max_velocity, std::cbrt(std::ranges::max(tolerances::plan_curvature_rate_jerk_shares) * 50000.0 * R * R) * (1 + 1e-12));
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
