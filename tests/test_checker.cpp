// The independent checker: planner output passes; a disturbed setpoint, a NaN or a jump is caught.
#include <gtest/gtest.h>

#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/verify/checker.hpp>
#include <limits>
#include <numbers>
#include <random>

#include "support/planner_run.hpp"
#include "support/random_curves.hpp"

namespace kontur::verify {
namespace {

struct Case {
  std::vector<std::shared_ptr<const Curve>> curves;
  std::vector<Sample> samples;
  std::vector<program::Move> moves;
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
  for (std::size_t i = 0; i < c.curves.size(); ++i) {
    c.moves.push_back(program::move_along(c.curves[i], 120.0, false, static_cast<long>(i + 1)));
    c.moves.back().id = static_cast<program::MoveId>(i);
  }
  c.samples = testing::plan_and_sample(m, c.moves);
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

// Regression guard: the lower level's replay of tolerance_parabolic_check2 (a full circle last)
// overshot the circle's end by 6e-8 mm one period before the exact end; the projection took that
// setpoint to the circle's start, the nearest point, and the chord to the end then spanned the
// whole circle: "a chord is 1.02 mm off the path". A setpoint a hair past the end of a closed move
// stays at its end.
TEST(Checker, ASetpointAHairPastTheEndOfAFullCircleStaysAtItsEnd) {
  const Machine m = default_machine();
  Case c;
  CircleFrame f;
  f.centre = {4.572, 5.588, 0};
  f.e1 = {1, 0, 0};
  f.e2 = {0, -1, 0};
  f.normal = {0, 0, -1};  // clockwise seen from +Z, as G2
  const double r = 0.508;
  c.curves = {std::make_shared<HelixArc>(f, r, 2.0 * std::numbers::pi, 0.0)};
  c.moves.push_back(program::move_along(c.curves[0], 60.0, false, 1));
  c.moves.back().id = 0;
  c.samples = testing::plan_and_sample(m, c.moves);
  ASSERT_GT(c.samples.size(), 10u);
  const Report plain = check(c.samples, c.moves, m);
  ASSERT_TRUE(plain.passed(m)) << ::testing::PrintToString(plain.failures(m));
  // the setpoint before the last: 6e-8 mm past the end (on the circle, at the start's side)
  auto past = c.samples;
  const double eps = 6e-8 / r;  // [rad]
  Sample& s = past[past.size() - 2];
  s.position.x() = f.centre.x() + r * std::cos(eps);
  s.position.y() = f.centre.y() - r * std::sin(eps);
  const Report rp = check(past, c.moves, m);
  EXPECT_LE(rp.max_chord_error_mm, m.chord_tolerance_mm) << ::testing::PrintToString(rp.failures(m));
  EXPECT_LE(rp.max_path_error_mm, 1e-7);
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
  const std::vector<program::Move> moves = {program::move_along(curve, 100.0, false, 1)};
  std::vector<Sample> samples = testing::plan_and_sample(m, moves);
  for (Sample& s : samples) s.move = program::no_move;  // as read from a file: matched by its line
  const Report r = check(samples, moves, m);
  EXPECT_LE(r.max_path_error_mm, 1e-9);
  EXPECT_EQ(r.end_error_mm, 0.0);
}

// Setpoints read from a file carry no move id: the checker matches them by their source line and
// must then find what it finds with the planner's ids.
TEST(Checker, SetpointsWithoutMoveIdsAreMatchedByLineAlike) {
  const Machine m = default_machine();
  const Case c = planned(m);
  auto anonymous = c.samples;
  for (Sample& s : anonymous) s.move = program::no_move;
  const Report a = check(c.samples, c.moves, m), b = check(anonymous, c.moves, m);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    EXPECT_EQ(a.blocks[i].samples, b.blocks[i].samples) << "move " << i;
    EXPECT_EQ(a.blocks[i].max_jerk_ratio, b.blocks[i].max_jerk_ratio) << "move " << i;
  }
  EXPECT_EQ(a.max_path_error_mm, b.max_path_error_mm);
}

// Regression: a canned cycle's feed down and rapid retract run along the same line with the same
// source line; matching by line and distance gave every setpoint of the feed to the retract (its
// block showed 0 setpoints in test-active-states.ngc). The planner's move ids match them exactly.
TEST(Checker, MoveIdsKeepAFeedAndItsRetractAlongTheSameLineApart) {
  const Machine m = default_machine();
  const Vec3 top(0, 0, 5), bottom(0, 0, -5);
  std::vector<program::Move> moves = {
      program::move_along(std::make_shared<LineSegment>(top, bottom), 10.0, true, 27),    // feed down
      program::move_along(std::make_shared<LineSegment>(bottom, top), 200.0, true, 27)};  // rapid up
  for (std::size_t i = 0; i < moves.size(); ++i) moves[i].id = static_cast<program::MoveId>(i);
  const std::vector<Sample> samples = testing::plan_and_sample(m, moves);
  const Report r = check(samples, moves, m);
  ASSERT_EQ(r.blocks.size(), 2u);
  long feed = 0;
  for (const Sample& s : samples) feed += s.move == 0 ? 1 : 0;
  EXPECT_EQ(r.blocks[0].samples, feed);
  EXPECT_GT(r.blocks[0].samples, 900);  // 10 mm at 10 mm/s: about a second
  EXPECT_EQ(r.blocks[0].samples + r.blocks[1].samples, static_cast<long>(samples.size()));
  EXPECT_TRUE(r.passed(m)) << ::testing::PrintToString(r.failures(m));
}

// The checker measures a blend's distance from its programmed corner its own way (samples and
// parabolic refinement); the blender sizes blends by dense samples and a golden-section search.
// Both must agree on seeded random corners, and a blend that leaves its tolerance must fail.
TEST(Checker, BlendDeviationAgreesWithTheBlendersOwnMeasure) {
  std::mt19937_64 rng(testing::test_seed());
  std::uniform_real_distribution<double> unit(-1.0, 1.0), trim(1e-4, 5.0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 t1 = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    Vec3 t2 = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
    if (t1.dot(t2) < -0.5) t2 = -t2;
    const Vec3 corner(unit(rng) * 100, unit(rng) * 100, unit(rng) * 100);
    const double d = trim(rng);
    const CornerBlendCurve blend(corner, t1, t2, d);
    const Vec3 before = corner - 2 * d * t1, after = corner + 2 * d * t2;
    const double theirs = corner_deviation(blend, before, corner, after);
    const double ours = blend_deviation(blend, {std::make_shared<const LineSegment>(before, corner),
                                                std::make_shared<const LineSegment>(corner, after), 1.0});
    EXPECT_NEAR(ours, theirs, 1e-12 * std::max(1.0, theirs)) << "corner " << i;
  }
}

// Regression (issue 12): another planner's setpoints carry block 0 (LinuxCNC's by default). On a
// path that comes back to a point it passed, the matcher took the later move that starts or ends
// there and never came back: 25 mm of "path error" on LinuxCNC's full_xy. The nearest point of
// the whole path is now searched where the matched move is off.
TEST(Checker, SetpointsWithoutLinesOnAPathThatComesBackStayOnThePath) {
  const Machine m = default_machine();
  auto line = [](Vec3 a, Vec3 b, long n) {
    return program::move_along(std::make_shared<LineSegment>(a, b), 100.0, true, n);
  };
  std::vector<program::Move> moves = {line({0, 0, 0}, {10, 0, 0}, 1), line({10, 0, 0}, {10, 10, 0}, 2),
                                      line({10, 10, 0}, {0, 0, 0}, 3), line({0, 0, 0}, {10, 0, 0}, 4),
                                      line({10, 0, 0}, {0, 10, 0}, 5)};
  for (std::size_t i = 0; i < moves.size(); ++i) moves[i].id = static_cast<program::MoveId>(i);
  std::vector<Sample> samples = testing::plan_and_sample(m, moves);
  for (Sample& s : samples) {
    s.move = program::no_move;
    s.source_line = 0;
  }
  const Report r = check(samples, moves, m);
  EXPECT_LE(r.max_path_error_mm, 1e-9);
  EXPECT_TRUE(r.passed(m)) << ::testing::PrintToString(r.failures(m));
  // A setpoint 0.3 mm off the path is measured as 0.3 mm from its nearest point, not from the
  // move the matcher expected.
  samples[samples.size() / 3].position[2] += 0.3;
  EXPECT_NEAR(check(samples, moves, m).max_path_error_mm, 0.3, 1e-9);
}

}  // namespace
}  // namespace kontur::verify
