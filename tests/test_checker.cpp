// The independent checker: planner output passes; a disturbed setpoint, a NaN or a jump is caught.
#include <gtest/gtest.h>
#include <kontur/helix_arc.hpp>
#include <kontur/line_segment.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/verify/checker.hpp>

#include <limits>
#include <numbers>

namespace kontur::verify {
namespace {

struct Case {
  std::vector<std::shared_ptr<const Curve>> curves;
  std::vector<Sample> samples;
  std::vector<PathMove> moves;
};

Case planned(const Machine& m) {
  Case c;
  CircleFrame f;
  f.centre = {50, 20, 0};
  f.e1 = {0, -1, 0};
  f.e2 = {1, 0, 0};
  c.curves = {std::make_shared<LineSegment>(Vec3(0, 0, 0), Vec3(50, 0, 0)),
              std::make_shared<HelixArc>(f, 20.0, std::numbers::pi / 2, 5.0),
              std::make_shared<LineSegment>(Vec3(70, 20, 5), Vec3(70, 0, 5))};
  plan::MotionPlanner p(m);
  for (std::size_t i = 0; i < c.curves.size(); ++i) {
    p.push({c.curves[i], 120.0, false, static_cast<long>(i + 1)});
    c.moves.push_back({c.curves[i].get(), static_cast<long>(i + 1)});
  }
  p.finish();
  plan::Setpoint sp;
  while (p.next(sp)) c.samples.push_back({sp.t_s, sp.position, sp.source_line});
  return c;
}

TEST(Checker, PlannerOutputPasses) {
  const Machine m = default_machine();
  const Case c = planned(m);
  const Report r = check(c.samples, c.moves, m);
  EXPECT_TRUE(r.passed(m)) << ::testing::PrintToString(r.failures(m));
  EXPECT_LE(r.max_path_error_mm, 1e-9);
  EXPECT_LE(r.max_chord_error_mm, m.chord_tolerance_mm);
  EXPECT_GT(r.max_velocity_ratio, 0.3);  // it did move at speed
}

TEST(Checker, CatchesADisturbedSetpointANaNAndAGap) {
  const Machine m = default_machine();
  Case c = planned(m);
  auto bumped = c.samples;
  bumped[bumped.size() / 2].position.y() += 1e-3;  // 1 um off
  Report r = check(bumped, c.moves, m);
  EXPECT_FALSE(r.passed(m));
  EXPECT_GT(r.max_jerk_ratio, 1.0);
  EXPECT_GT(r.max_path_error_mm, 0.9e-3);  // 1 um in y, not quite normal to the path
  EXPECT_LE(r.max_path_error_mm, 1e-3 + 1e-12);
  auto nan = c.samples;
  nan[10].position.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(check(nan, c.moves, m).finite);
  auto gap = c.samples;
  gap.erase(gap.begin() + 100);
  for (std::size_t k = 100; k < gap.size(); ++k) gap[k].t_s -= m.servo_period_s;  // time still uniform
  r = check(gap, c.moves, m);
  EXPECT_FALSE(r.passed(m));
  EXPECT_FALSE(r.failures(m).empty());
  auto short_end = c.samples;
  short_end.pop_back();
  EXPECT_GT(check(short_end, c.moves, m).end_error_mm, 0.0);
}

}  // namespace
}  // namespace kontur::verify
