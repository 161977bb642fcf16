// The data behind `kontur run --report`: the streaming decimation keeps every extremum exactly,
// and the checker's per-block statistics and per-setpoint measures agree with a brute-force
// recomputation from the setpoints and the path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <kontur/error.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/report/html_report.hpp>
#include <kontur/verify/checker.hpp>
#include <numbers>

#include "support/planner_run.hpp"
#include <random>

namespace kontur {
namespace {

TEST(StreamDecimator, KeepsTheGlobalExtremaOfEveryChannelExactly) {
  std::mt19937_64 rng(20261122);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_int_distribution<int> sizes(1, 300000);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = trial < 3 ? static_cast<std::size_t>(trial + 1) : static_cast<std::size_t>(sizes(rng));
    const std::size_t channels = 1 + static_cast<std::size_t>(trial % 4),
                      buckets = 50 + 37 * static_cast<std::size_t>(trial);
    report::StreamDecimator d(channels, buckets);
    std::vector<std::vector<double>> all(channels);
    std::vector<double> values(channels);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t c = 0; c < channels; ++c) {
        // A random walk with rare spikes (a one-sample spike must survive).
        const double prev = all[c].empty() ? 0.0 : all[c].back();
        values[c] = prev + noise(rng) + (rng() % 5000 == 0 ? 1e3 * noise(rng) : 0.0);
        all[c].push_back(values[c]);
      }
      d.add(0.001 * static_cast<double>(i), values);
    }
    ASSERT_EQ(d.count(), n);
    const auto k = d.kept();
    ASSERT_FALSE(k.index.empty());
    EXPECT_LE(k.index.size(), 2 * buckets * (2 + 2 * channels)) << "n = " << n;
    EXPECT_TRUE(std::is_sorted(k.index.begin(), k.index.end()));
    EXPECT_EQ(std::adjacent_find(k.index.begin(), k.index.end()), k.index.end());  // unique
    EXPECT_EQ(k.index.front(), 0u);
    EXPECT_EQ(k.index.back(), n - 1);
    for (std::size_t i = 0; i < k.index.size(); ++i) {
      // Every kept sample is a real one, with its own x and values.
      EXPECT_EQ(k.x[i], 0.001 * static_cast<double>(k.index[i]));
      for (std::size_t c = 0; c < channels; ++c) ASSERT_EQ(k.values[i * channels + c], all[c][k.index[i]]);
    }
    for (std::size_t c = 0; c < channels; ++c) {
      const auto [lo, hi] = std::minmax_element(all[c].begin(), all[c].end());
      double klo = INFINITY, khi = -INFINITY;
      for (std::size_t i = 0; i < k.index.size(); ++i) {
        klo = std::min(klo, k.values[i * channels + c]);
        khi = std::max(khi, k.values[i * channels + c]);
      }
      EXPECT_EQ(klo, *lo) << "trial " << trial << " channel " << c;
      EXPECT_EQ(khi, *hi) << "trial " << trial << " channel " << c;
      // The first occurrence of each global extremum is the one kept.
      EXPECT_TRUE(std::binary_search(k.index.begin(), k.index.end(), static_cast<std::size_t>(lo - all[c].begin())));
      EXPECT_TRUE(std::binary_search(k.index.begin(), k.index.end(), static_cast<std::size_t>(hi - all[c].begin())));
    }
  }
}

TEST(StreamDecimator, KeepsSmallDataWholeAndBoundsMemory) {
  report::StreamDecimator d(1, 100);
  for (int i = 0; i < 150; ++i) {
    const double v = std::sin(i);
    d.add(i, std::span<const double>(&v, 1));
  }
  EXPECT_EQ(d.kept().index.size(), 150u);  // 150 < 2 * 100 buckets of one sample
  const double bad[2] = {1, 2};
  EXPECT_THROW(d.add(0, bad), InputError);
}

TEST(DecimateMinMax, KeepsTheGlobalExtremaOfSeededRandomSeries) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (std::size_t n : {10u, 1000u, 123457u}) {
    std::vector<double> a(n), b(n);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = u(rng);
      b[i] = std::sin(0.001 * static_cast<double>(i)) + 1e-6 * u(rng);
    }
    const std::vector<std::span<const double>> ch = {a, b};
    const auto keep = report::decimate_min_max(n, 97, ch);
    for (const auto* v : {&a, &b}) {
      double lo = INFINITY, hi = -INFINITY;
      for (const std::size_t i : keep) {
        lo = std::min(lo, (*v)[i]);
        hi = std::max(hi, (*v)[i]);
      }
      EXPECT_EQ(lo, *std::min_element(v->begin(), v->end()));
      EXPECT_EQ(hi, *std::max_element(v->begin(), v->end()));
    }
  }
}

// Brute-force distance of p from a curve: 20001 samples, then 20001 more between the best one's
// neighbours (no Newton, nothing shared with the checker).
double brute_distance(const Curve& c, const Vec3& p) {
  auto best_in = [&](double a, double b, double& u_best) {
    double best = INFINITY;
    for (int i = 0; i <= 20000; ++i) {
      const double u = a + (b - a) * i / 20000.0;
      const double d = (c.point(u) - p).norm();
      if (d < best) {
        best = d;
        u_best = u;
      }
    }
    return best;
  };
  double u = c.u_min();
  best_in(c.u_min(), c.u_max(), u);
  const double h = (c.u_max() - c.u_min()) / 20000.0;
  return best_in(std::max(c.u_min(), u - h), std::min(c.u_max(), u + h), u);
}

TEST(Checker, PerBlockStatisticsMatchABruteForceRecomputation) {
  const Machine m = default_machine();
  CircleFrame f;
  f.centre = {50, 20, 0};
  f.e1 = {0, -1, 0};
  f.e2 = {1, 0, 0};
  const std::vector<std::shared_ptr<const Curve>> curves = {
      std::make_shared<LineSegment>(Vec3(0, 0, 0), Vec3(50, 0, 0)),
      std::make_shared<HelixArc>(f, 20.0, std::numbers::pi / 2, 5.0),
      std::make_shared<LineSegment>(Vec3(70, 20, 5), Vec3(70, 0, 5)),
      std::make_shared<LineSegment>(Vec3(70, 0, 5), Vec3(40, -10, 0))};
  std::vector<program::Move> moves;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    moves.push_back(program::move_along(curves[i], 150.0, i == 2, static_cast<long>(10 * (i + 1))));
    moves.back().id = static_cast<program::MoveId>(i);
  }
  std::vector<verify::Sample> s = testing::plan_and_sample(m, moves);
  // Disturb one setpoint inside each block (by different amounts) so that every block has a
  // path error and jerk of its own.
  std::vector<std::size_t> bumped;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    std::vector<std::size_t> on;
    for (std::size_t k = 0; k < s.size(); ++k)
      if (s[k].source_line == moves[i].source_line) on.push_back(k);
    ASSERT_GT(on.size(), 20u);
    const std::size_t k = on[on.size() / 2];
    s[k].position[2] += 1e-4 * static_cast<double>(i + 1);
    bumped.push_back(k);
  }
  std::vector<verify::SampleMeasure> seen;
  const verify::Report r = verify::check(s, moves, m, [&](const verify::SampleMeasure& x) { seen.push_back(x); });
  ASSERT_EQ(r.blocks.size(), moves.size());
  ASSERT_EQ(seen.size(), s.size());
  const double T = m.servo_period_s;
  double all_v = 0, all_a = 0, all_j = 0, all_path = 0, all_chord = 0;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const verify::BlockStats& b = r.blocks[i];
    // Brute force: the setpoints of the block are those with its source line (lines are unique
    // here); the ratios are the differences ending at each of them.
    long first = -1, last = -1, count = 0;
    double v = 0, a = 0, j = 0, path = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
      if (s[k].source_line != moves[i].source_line) continue;
      if (first < 0) first = static_cast<long>(k);
      last = static_cast<long>(k);
      ++count;
      for (const AxisLimits& ax : m.axes) {
        const int c = linear_axis_index(ax.name);
        if (c < 0) continue;
        auto x = [&](std::size_t q) { return s[q].position[c]; };
        if (k >= 1) v = std::max(v, std::abs(x(k) - x(k - 1)) / T / ax.max_velocity);
        if (k >= 2) a = std::max(a, std::abs(x(k) - 2 * x(k - 1) + x(k - 2)) / (T * T) / ax.max_acceleration);
        if (k >= 3)
          j = std::max(j, std::abs(x(k) - 3 * x(k - 1) + 3 * x(k - 2) - x(k - 3)) / (T * T * T) / ax.max_jerk);
      }
      path = std::max(path, brute_distance(*curves[i], Vec3(s[k].position)));
      EXPECT_EQ(seen[k].move, i) << "setpoint " << k;
    }
    EXPECT_EQ(b.source_line, moves[i].source_line);
    EXPECT_EQ(b.samples, count);
    EXPECT_EQ(b.first_sample, first);
    EXPECT_EQ(b.last_sample, last);
    EXPECT_EQ(b.t_first_s, s[static_cast<std::size_t>(first)].t_s);
    EXPECT_EQ(b.t_last_s, s[static_cast<std::size_t>(last)].t_s);
    EXPECT_NEAR(b.max_velocity_ratio, v, 1e-12 * v);
    EXPECT_NEAR(b.max_acceleration_ratio, a, 1e-12 * a);
    EXPECT_NEAR(b.max_jerk_ratio, j, 1e-12 * j);
    EXPECT_NEAR(b.max_path_error_mm, path, 1e-9) << "block " << i;
    EXPECT_GT(b.max_path_error_mm, 0.5e-4 * static_cast<double>(i + 1));  // its own bump, seen
    all_v = std::max(all_v, b.max_velocity_ratio);
    all_a = std::max(all_a, b.max_acceleration_ratio);
    all_j = std::max(all_j, b.max_jerk_ratio);
    all_path = std::max(all_path, b.max_path_error_mm);
    all_chord = std::max(all_chord, b.max_chord_error_mm);
  }
  // The blocks' maxima are the program's.
  EXPECT_EQ(all_v, r.max_velocity_ratio);
  EXPECT_EQ(all_a, r.max_acceleration_ratio);
  EXPECT_EQ(all_j, r.max_jerk_ratio);
  EXPECT_EQ(all_path, r.max_path_error_mm);
  EXPECT_EQ(all_chord, r.max_chord_error_mm);
  // The per-setpoint measures: the finite differences, as checked, and the errors.
  double chord_max = 0.0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto& x = seen[k];
    EXPECT_EQ(x.index, k);
    EXPECT_EQ(x.t_s, s[k].t_s);
    if (k >= 1) {
      EXPECT_LE((x.velocity - (s[k].position - s[k - 1].position) / T).norm(), 1e-9);
    }
    if (k >= 3) {
      EXPECT_LE(
          (x.jerk - (s[k].position - 3 * s[k - 1].position + 3 * s[k - 2].position - s[k - 3].position) / (T * T * T))
              .norm(),
          1e-9 * std::max(1.0, x.jerk.norm()));
    }
    chord_max = std::max(chord_max, x.chord_error_mm);
  }
  EXPECT_EQ(chord_max, r.max_chord_error_mm);
  EXPECT_EQ(seen[bumped[3]].path_error_mm, r.max_path_error_mm);
  // The three-argument check gives the same report.
  const verify::Report r3 = verify::check(s, moves, m);
  EXPECT_EQ(r3.max_jerk_ratio, r.max_jerk_ratio);
  EXPECT_EQ(r3.worst_jerk_axis, r.worst_jerk_axis);
  EXPECT_EQ(r3.blocks.size(), r.blocks.size());
}

}  // namespace
}  // namespace kontur
