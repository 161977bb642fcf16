// The profile of a curved piece alone in its chain with an acceleration bound by speed band
// (plan/banded_profile.hpp): every sample within the band's acceleration at its speed and the jerk
// limit, continuous, ending exactly at the length and end speed; never slower than the S-curve at
// the last band's acceleration; and the bands computed from a circle's geometry keep every axis
// within its limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <kontur/plan/banded_profile.hpp>
#include <kontur/plan/constraints.hpp>
#include "support/machine_limits.hpp"
#include <random>
#include <vector>

namespace kontur::plan {
namespace {

using trajectory::PathProfile;

// Random bands: ascending tops up to the cap, non-increasing accelerations.
AccelerationBands random_bands(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  AccelerationBands b;
  b.n = 1 + static_cast<int>(u(rng) * 5.0);
  const double cap = 1.0 + 400.0 * u(rng);
  double a = 50.0 + 3000.0 * u(rng);
  double top = 0.0;
  for (int k = 0; k < b.n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    top = k + 1 == b.n ? cap : top + (cap - top) * (0.1 + 0.8 * u(rng));
    b.top_mm_s[kk] = top;
    b.acceleration[kk] = a;
    a *= 0.2 + 0.8 * u(rng);
  }
  b.max_jerk = 1e3 + 1e6 * u(rng);
  return b;
}

// Samples the profile every dt: s and v continuous, v >= 0 and <= the cap, |a| within the band of
// the speed (at the higher speed of the sample's neighbourhood), |j| <= J, the end exact.
void expect_valid(const PathProfile& p, const AccelerationBands& b, double distance, double v1) {
  const double cap = b.top_mm_s[static_cast<std::size_t>(b.n - 1)];
  const int n = 20000;
  const double dt = p.duration() / n;
  auto prev = p.sample(0.0);
  for (int k = 1; k <= n; ++k) {
    const auto x = p.sample(k * dt);
    ASSERT_GE(x.v, -1e-9 * cap) << k;
    ASSERT_LE(x.v, cap * (1.0 + 1e-9)) << k;
    ASSERT_LE(std::abs(x.a), b.at(x.v) * (1.0 + 1e-9) + 1e-9) << "at v " << x.v << ", step " << k;
    ASSERT_LE(std::abs(x.j), b.max_jerk * (1.0 + 1e-9)) << k;
    // continuity: the distance and speed move by what the speed and acceleration allow in dt
    // (the trapezoid rule's error where the acceleration or jerk changes within the step)
    const double a_top = b.acceleration[0];
    ASSERT_NEAR(x.s - prev.s, 0.5 * (x.v + prev.v) * dt, a_top * dt * dt + b.max_jerk * dt * dt * dt + 1e-12 * distance)
        << k;
    ASSERT_NEAR(x.v - prev.v, 0.5 * (x.a + prev.a) * dt, b.max_jerk * dt * dt + 1e-12 * cap) << k;
    prev = x;
  }
  EXPECT_EQ(p.sample(p.duration()).s, distance);
  EXPECT_NEAR(p.sample(p.duration()).v, v1, 1e-9 * (1.0 + cap));
}

TEST(BandedProfile, KeepsEachBandsAccelerationTheJerkAndTheEndsOnSeededRandomProblems) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int planned = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const AccelerationBands b = random_bands(rng);
    const double cap = b.top_mm_s[static_cast<std::size_t>(b.n - 1)];
    const double last_a = b.acceleration[static_cast<std::size_t>(b.n - 1)];
    const double distance = std::pow(10.0, -3.0 + 5.0 * u(rng));
    const PathLimits l{cap, last_a, b.max_jerk};
    // start and end speeds the look-ahead could plan with the last band's acceleration
    const double v0 = u(rng) < 0.3 ? 0.0 : std::min(cap, reachable_velocity(0.0, distance, l)) * u(rng);
    const double v1 = u(rng) < 0.3 ? 0.0 : reachable_velocity(v0, distance, l) * u(rng);
    const ScurveProfile s = plan_scurve(distance, v0, v1, l);
    const auto p = plan_banded_profile(distance, v0, s.end_velocity(), b);
    ASSERT_TRUE(p) << trial;
    ++planned;
    SCOPED_TRACE(trial);
    expect_valid(*p, b, distance, s.end_velocity());
    // more acceleration at low speed never makes it slower than the S-curve at the last band's
    EXPECT_LE(p->duration(), s.duration() * (1.0 + 1e-9)) << trial;
  }
  EXPECT_EQ(planned, 400);
}

TEST(BandedProfile, OneBandIsTheScurve) {
  AccelerationBands b;
  b.n = 1;
  b.top_mm_s[0] = 80.0;
  b.acceleration[0] = 600.0;
  b.max_jerk = 20000.0;
  const ScurveProfile s = plan_scurve(50.0, 0.0, 0.0, {80.0, 600.0, 20000.0});
  const auto p = plan_banded_profile(50.0, 0.0, 0.0, b);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->duration(), s.duration(), 1e-12 * s.duration());
  EXPECT_NEAR(banded_change_time(0.0, 80.0, b), velocity_change_time(0.0, 80.0, 600.0, 20000.0), 1e-12);
}

// The time a change loses within a stretch: where the change fits, its duration less its distance
// over the cap, whatever the stretch's length beyond; where it does not, the time to run the
// stretch's length speeding up (the change to the speed reached there covers exactly that length)
// less that length over the cap: positive, and less than the whole change's duration.
TEST(BandedProfile, TheTimeAChangeLosesCountsOnlyTheDistanceItHas) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const AccelerationBands b = random_bands(rng);
    const double cap = b.top_mm_s[static_cast<std::size_t>(b.n - 1)];
    const double from = 0.5 * cap * u(rng);
    const double whole = banded_change_distance(from, cap, b);  // [mm]
    const double lost = banded_change_time_lost(from, cap, b);  // [s]
    ASSERT_TRUE(std::isfinite(whole) && std::isfinite(lost)) << trial;
    EXPECT_EQ(banded_change_time_lost(from, cap, b, whole * (1.0 + u(rng))), lost) << trial;
    for (const double share : {0.9, 0.5, 0.1}) {
      const double within = share * whole;  // [mm]
      const double reached = banded_reachable_velocity(from, within, b);
      ASSERT_LT(reached, cap) << trial;
      EXPECT_NEAR(banded_change_distance(from, reached, b), within, 1e-6 * whole) << trial;
      const double short_lost = banded_change_time_lost(from, cap, b, within);
      EXPECT_NEAR(short_lost, banded_change_time(from, reached, b) - within / cap, 1e-12 * (1.0 + short_lost)) << trial;
      EXPECT_GT(short_lost, 0.0) << trial;
      EXPECT_LT(short_lost, banded_change_time(from, cap, b)) << trial;
    }
  }
}

TEST(BandedProfile, RefusesWhatItCannotPlan) {
  AccelerationBands b;
  EXPECT_FALSE(plan_banded_profile(10.0, 0.0, 0.0, b));  // no bands
  b.n = 2;
  b.top_mm_s = {20.0, 10.0};  // tops not ascending
  b.acceleration = {200.0, 100.0};
  b.max_jerk = 1000.0;
  EXPECT_FALSE(plan_banded_profile(10.0, 0.0, 0.0, b));
  b.top_mm_s = {10.0, 20.0};
  EXPECT_FALSE(plan_banded_profile(10.0, 25.0, 0.0, b));      // faster than the cap
  EXPECT_FALSE(plan_banded_profile(1e-6, 20.0, 0.0, b));      // the braking alone does not fit
  EXPECT_TRUE(plan_banded_profile(10.0, 0.0, 0.0, b));
}

// Random bands whose accelerations may rise with the speed (a chain profile's change of speed runs
// through tight stretches only at its slow end: chain_profile.cpp's change_bands).
AccelerationBands random_rising_bands(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  AccelerationBands b;
  b.n = 1 + static_cast<int>(u(rng) * 8.0);
  const double cap = 1.0 + 400.0 * u(rng);
  double top = 0.0;
  for (int k = 0; k < b.n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    top = k + 1 == b.n ? cap : top + (cap - top) * (0.1 + 0.6 * u(rng));
    b.top_mm_s[kk] = top;
    b.acceleration[kk] = 50.0 + 3000.0 * u(rng);
  }
  b.max_jerk = 1e3 + 1e6 * u(rng);
  return b;
}

// The fastest change's duration found independently, by quadrature: its squared acceleration g(v)
// is the largest with |dg/dv| <= 2J (the jerk bound), g <= a_max(v)^2 and g = 0 at both ends: the
// least of 2J (v - va), 2J (vb - v) and, for each band k, a_k^2 + 2J times the distance from v to
// the band's speeds; the time is the integral of dv / sqrt(g) over a fine grid (a sweep and a
// breakdown into pieces in banded_profile.cpp, a direct minimum and a quadrature here).
double brute_force_change_time(double va, double vb, const AccelerationBands& b) {
  const int n = 100000;
  const double h = (vb - va) / n;
  const auto g = [&](double v) {
    double best = 2.0 * b.max_jerk * std::max(0.0, std::min(v - va, vb - v));
    for (int k = 0; k < b.n; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const double lo = k == 0 ? 0.0 : b.top_mm_s[kk - 1], hi = k + 1 == b.n ? 1e300 : b.top_mm_s[kk];
      const double away = v < lo ? lo - v : (v > hi ? v - hi : 0.0);
      best = std::min(best, b.acceleration[kk] * b.acceleration[kk] + 2.0 * b.max_jerk * away);
    }
    return best;
  };
  // Each grid interval with g linear inside: its time in closed form, 2 h / (sqrt g0 + sqrt g1);
  // the kinks of g between grid points add O(h^2).
  double t = 0.0;
  for (int i = 0; i < n; ++i) t += 2.0 * h / (std::sqrt(g(va + i * h)) + std::sqrt(g(va + (i + 1) * h)));
  return t;
}

TEST(BandedProfile, RisingBandsTakeTheFastestChangeAndKeepEachBandsAcceleration) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE(trial);
    const AccelerationBands b = random_rising_bands(rng);
    const double cap = b.top_mm_s[static_cast<std::size_t>(b.n - 1)];
    const double va = 0.6 * cap * u(rng), vb = va + (cap - va) * (0.2 + 0.8 * u(rng));
    const double t = banded_change_time(va, vb, b);
    ASSERT_TRUE(std::isfinite(t));
    // (the quadrature converges to it: 1.4e-4, 1.4e-5 and 1.4e-6 of it off with 5,000, 20,000 and
    // 80,000 intervals on the worst of these problems)
    EXPECT_NEAR(t, brute_force_change_time(va, vb, b), 1e-5 * t);
    // the profile over a length that fits the change: within each band's acceleration at its speed
    const double distance = banded_change_distance(va, vb, b) * (1.0 + 2.0 * u(rng));
    const bool up = u(rng) < 0.5;
    const auto p = plan_banded_profile(distance, up ? va : vb, up ? vb : va, b);
    ASSERT_TRUE(p);
    expect_valid(*p, b, distance, up ? vb : va);
    // never slower than the S-curve at the smallest of the bands' accelerations
    double least = b.acceleration[0];
    for (int k = 1; k < b.n; ++k) least = std::min(least, b.acceleration[static_cast<std::size_t>(k)]);
    EXPECT_LE(t, velocity_change_time(va, vb, least, b.max_jerk) * (1.0 + 1e-9));
  }
}

// A band that leaves more acceleration above a tight one: the change runs up to the tight band's
// acceleration, flat along it, and rises again at the jerk limit once past its top (not before).
TEST(BandedProfile, ARisingBandIsUsedOnlyOnceTheSpeedIsInIt) {
  AccelerationBands b;
  b.n = 2;
  b.top_mm_s = {10.0, 40.0};
  b.acceleration = {100.0, 400.0};
  b.max_jerk = 10000.0;
  const auto p = plan_banded_profile(1000.0, 0.0, 40.0, b);
  ASSERT_TRUE(p);
  expect_valid(*p, b, 1000.0, 40.0);
  double peak_below = 0.0, peak_above = 0.0;  // [mm/s^2]
  for (int k = 0; k <= 4000; ++k) {
    const auto x = p->sample(p->duration() * k / 4000.0);
    (x.v <= 10.0 ? peak_below : peak_above) = std::max(x.v <= 10.0 ? peak_below : peak_above, x.a);
  }
  EXPECT_NEAR(peak_below, 100.0, 1e-6);
  EXPECT_GT(peak_above, 200.0);  // (the S-curve at 100 throughout would stay at 100)
  // faster than at the tight band's acceleration throughout, slower than at the wide one's
  EXPECT_LT(banded_change_time(0.0, 40.0, b), velocity_change_time(0.0, 40.0, 100.0, 10000.0));
  EXPECT_GT(banded_change_time(0.0, 40.0, b), velocity_change_time(0.0, 40.0, 400.0, 10000.0));
}

// A circle of radius R in XY on a machine of A per axis: the bands let the path accelerate at
// about sqrt(A^2 - (v^2 / R)^2) below the cap; sampled along the circle, every axis's acceleration
// t_i a + K_i v^2 (and the cross term of the jerk) stays within its limits.
TEST(BandedProfile, ACirclesBandsKeepEveryAxisWithinItsAcceleration) {
  Machine m;
  m.max_feed_mm_s = 1000.0;
  m.rapid_feed_mm_s = 1000.0;
  m.chord_tolerance_mm = 0.001;
  m.path_tolerance_mm = 0.01;
  m.servo_period_s = 0.001;
  for (const char name : {'X', 'Y', 'Z'}) m.axes.push_back(AxisLimits{.name = name});
  testing::set_every_axis(m, 200.0, 762.0, 76200.0);
  const double r = 25.4;
  PathGeometry g;
  std::vector<std::array<double, 2>> px, py;
  for (int k = 0; k <= 64; ++k) {
    const double th = 2.0 * M_PI * k / 64.0;
    px.push_back({std::abs(std::sin(th)), std::abs(std::cos(th)) / r});
    py.push_back({std::abs(std::cos(th)), std::abs(std::sin(th)) / r});
  }
  g.tangent = Vec3(1.0, 1.0, 0.0);
  g.curvature = Vec3(1.0 / r, 1.0 / r, 0.0);
  g.curvature_rate = Vec3(1.0 / (r * r), 1.0 / (r * r), 0.0);
  g.max_kappa = 1.0 / r;
  g.set_pairs(0, px);
  g.set_pairs(1, py);
  const PathLimits l = path_limits(g, 120.0, 1000.0, m, {.alone = true});
  const AccelerationBands b = acceleration_bands(g, l, m, 0.0);
  ASSERT_GT(b.n, 1);
  EXPECT_EQ(b.top_mm_s[static_cast<std::size_t>(b.n - 1)], l.max_velocity);
  EXPECT_EQ(b.acceleration[static_cast<std::size_t>(b.n - 1)], l.max_acceleration);
  EXPECT_GT(b.acceleration[0], 1.5 * l.max_acceleration);
  EXPECT_LE(b.max_jerk, l.max_jerk);
  const auto p = plan_banded_profile(120.0, 0.0, 0.0, b);
  ASSERT_TRUE(p);
  EXPECT_LT(p->duration(), plan_scurve(120.0, 0.0, 0.0, l).duration());
  for (int k = 0; k <= 4000; ++k) {
    const auto x = p->sample(p->duration() * k / 4000.0);
    const double th = x.s / r;
    // the axes' acceleration on the circle: the tangential part along t, the centripetal along -n
    const double ax = -std::sin(th) * x.a - std::cos(th) * x.v * x.v / r;
    const double ay = std::cos(th) * x.a - std::sin(th) * x.v * x.v / r;
    ASSERT_LE(std::abs(ax), 762.0 * (1.0 + 1e-9)) << k;
    ASSERT_LE(std::abs(ay), 762.0 * (1.0 + 1e-9)) << k;
  }
}

}  // namespace
}  // namespace kontur::plan
