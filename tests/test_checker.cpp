// The independent checker: planner output passes; a disturbed setpoint, a NaN or a jump is caught.
#include <gtest/gtest.h>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>
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

// Regression guard: on a NURBS with uneven weights (the curve moves very unevenly in u, as in
// LinuxCNC's G6_Curva_Delfino with R46 next to R1) a projection from 64 samples over the whole
// range found a wrong local minimum and reported setpoints 1.39 mm off a path they were on.
TEST(Checker, ProjectionOnAnUnevenlyWeightedNurbs) {
  NurbsData d;
  d.degree = 3;
  d.knots = {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1};
  d.points = {{0, 0, 0}, {10, 5, 0}, {20, -5, 0}, {30, 10, 0}, {40, 0, 0}, {50, 3, 0}};
  d.weights = {1, 46, 1, 0.03, 34, 1};
  auto curve = std::make_shared<NurbsCurve>(d);
  const Machine m = default_machine();
  plan::MotionPlanner p(m);
  p.push({curve, 100.0, false, 1});
  p.finish();
  std::vector<Sample> samples;
  plan::Setpoint sp;
  while (p.next(sp)) samples.push_back({sp.t_s, sp.position, sp.source_line});
  const Report r = check(samples, {{curve.get(), 1}}, m);
  EXPECT_LE(r.max_path_error_mm, 1e-9);
  EXPECT_EQ(r.end_error_mm, 0.0);
}

}  // namespace
}  // namespace kontur::verify
