// Corner blending within the G64 tolerance (program/corner_blender.hpp): every blend within its
// tolerance of the programmed lines, curvature-continuous at both ends, none under exact stop,
// lines between blends keep a straight middle, and a blended square passes the check faster.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/program/corner_blender.hpp>
#include <kontur/verify/checker.hpp>
#include <memory>
#include <random>
#include <vector>

#include "support/planner_run.hpp"

namespace kontur {
namespace {

// A line move with the G64 tolerance `tol_mm` at its end.
program::Move line_move(const Vec3& a, const Vec3& b, double tol_mm, double feed_mm_s = 100.0, bool exact_stop = false,
                        long line = 1) {
  program::Move m = program::move_along(std::make_shared<const LineSegment>(a, b), feed_mm_s, exact_stop, line);
  m.corner_tolerance_mm = tol_mm;
  return m;
}

// The moves the blender makes of a polyline (tolerance `tol_mm` at every corner); line i + 1 is
// the programmed segment from pts[i] to pts[i + 1].
std::vector<program::Move> blend_polyline(const std::vector<Vec3>& pts, double tol_mm, bool enabled = true) {
  program::CornerBlender blender(enabled);
  std::vector<program::Move> out;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i)
    blender.push(line_move(pts[i], pts[i + 1], tol_mm, 100.0, false, static_cast<long>(i + 1)), out);
  blender.flush(out);
  return out;
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vec3 v(n(rng), n(rng), n(rng));
  return v.normalized();
}

TEST(CornerBlend, DeviationWithinToleranceOnRandomCorners) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> len(0.01, 50.0), tol(1e-4, 0.1), coord(-500.0, 500.0);
  int blends = 0, at_tolerance = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(coord(rng), coord(rng), coord(rng));
    const Vec3 t1 = random_unit(rng), t2 = random_unit(rng);
    const double delta = tol(rng);
    const std::vector<Vec3> pts = {p - len(rng) * t1, p, p + len(rng) * t2};
    const auto out = blend_polyline(pts, delta);
    for (const auto& bm : out) {
      if (!bm.corner) continue;
      ++blends;
      const double dev = verify::blend_deviation(*bm.curve, *bm.corner);
      EXPECT_LE(dev, delta * (1 + 1e-9)) << "corner " << i;
      if (dev >= 0.99 * delta) ++at_tolerance;
    }
    if (t1.dot(t2) >= -0.5) {
      EXPECT_EQ(out.size(), 3U) << "corner " << i << " not blended";
    } else {
      EXPECT_EQ(out.size(), 2U) << "corner " << i << " turns by more than 120 degrees: kept";
    }
  }
  EXPECT_GT(blends, 1000);
  EXPECT_GT(at_tolerance, 100);  // where the lines are long enough, the blend uses its tolerance
}

TEST(CornerBlend, CurvatureContinuousAtBothEnds) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p = 100.0 * random_unit(rng);
    const Vec3 t1 = random_unit(rng), t2 = random_unit(rng);
    if (t1.dot(t2) < -0.5) continue;
    const std::vector<Vec3> pts = {p - 10.0 * t1, p, p + 7.0 * t2};
    const auto out = blend_polyline(pts, 0.01);
    ASSERT_EQ(out.size(), 3U);
    const Curve& c = *out[1].curve;
    for (const auto& [u, t] : {std::pair{0.0, t1}, std::pair{1.0, t2}}) {
      const Derivatives d = c.derivatives(u, 2);
      const Vec3 tangent = d[1].normalized();
      const Vec3 curvature = (d[2] - d[2].dot(tangent) * tangent) / d[1].squaredNorm();  // [1/mm]
      EXPECT_LT((tangent - t).norm(), 1e-9);
      EXPECT_LT(curvature.norm(), 1e-9);  // a line's curvature is zero
    }
    // The pieces join: the incoming line ends where the blend starts, the outgoing starts where it ends.
    EXPECT_LT((out[0].curve->point(1.0) - c.point(0.0)).norm(), 1e-12);
    EXPECT_LT((out[2].curve->point(0.0) - c.point(1.0)).norm(), 1e-12);
    EXPECT_LT((out[0].curve->point(0.0) - pts[0]).norm(), 1e-12);
    EXPECT_LT((out[2].curve->point(1.0) - pts[2]).norm(), 1e-12);
  }
}

TEST(CornerBlend, ExactStopKeepsTheCorner) {
  program::CornerBlender blender;
  std::vector<program::Move> out;
  blender.push(line_move({0, 0, 0}, {10, 0, 0}, 0.01, 100.0, true), out);  // G61
  blender.push(line_move({10, 0, 0}, {10, 10, 0}, 0.01), out);
  blender.flush(out);
  ASSERT_EQ(out.size(), 2U);
  for (const auto& bm : out) EXPECT_FALSE(bm.corner);
  // A tolerance of zero (corner_tolerance under G61 / G61.1) keeps it too.
  EXPECT_EQ(blend_polyline({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}}, 0.0).size(), 2U);
  // And so does --no-blend.
  EXPECT_EQ(blend_polyline({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}}, 0.01, false).size(), 2U);
  EXPECT_EQ(blend_polyline({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}}, 0.01).size(), 3U);
}

TEST(CornerBlend, ShortLinesKeepAStraightMiddle) {
  // A zigzag of lines of very different lengths with a large tolerance: every trim is limited by
  // the lines, and consecutive moves join.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> len(1e-3, 2.0), ang(-1.5, 1.5);
  std::vector<Vec3> pts = {Vec3::Zero()};
  double heading = 0.0;
  for (int i = 0; i < 500; ++i) {
    heading += ang(rng);
    pts.push_back(pts.back() + len(rng) * Vec3(std::cos(heading), std::sin(heading), 0.0));
  }
  const auto out = blend_polyline(pts, 1.0);
  int blends = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Curve& c = *out[i].curve;
    if (out[i].corner) {
      ++blends;
      continue;
    }
    const auto* l = dynamic_cast<const LineSegment*>(&c);
    ASSERT_NE(l, nullptr);
    const auto tag = static_cast<std::size_t>(out[i].source_line - 1);
    const double programmed = (pts[tag + 1] - pts[tag]).norm();
    EXPECT_GE(l->length_mm(), (1.0 - 2 * 0.45) * programmed * (1 - 1e-9));
    // Along the programmed line, in its direction.
    EXPECT_GT((l->end() - l->start()).dot(pts[tag + 1] - pts[tag]), 0.0);
    if (i > 0) {
      EXPECT_LT((out[i - 1].curve->point(1.0) - c.point(0.0)).norm(), 1e-12);
    }
  }
  EXPECT_GT(blends, 400);
}

struct RunResult {
  verify::Report report;
  double time_s = 0.0;
};

// A square and a little more (its corners turn by 90 degrees), or a 36-gon of radius 20 mm
// (10 degrees), as lines at 150 mm/s.
RunResult run_polygon(bool blend, const Machine& machine, int sides = 4) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= sides + 1; ++i) {
    const double a = 2.0 * M_PI * i / sides;
    pts.emplace_back(20.0 * std::cos(a), 20.0 * std::sin(a), 0.0);
  }
  program::CornerBlender blender(
      blend, &machine, [&](const Curve& c, double feed_mm_s) { return plan::curve_speed_cap(c, feed_mm_s, machine); });
  std::vector<program::Move> moves;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i)
    blender.push(line_move(pts[i], pts[i + 1], machine.path_tolerance_mm, 150.0, false, static_cast<long>(i + 1)),
                 moves);
  blender.flush(moves);
  const std::vector<verify::Sample> samples = testing::plan_and_sample(machine, moves);
  for (std::size_t i = 0; i < moves.size(); ++i) moves[i].id = static_cast<program::MoveId>(i);
  return {verify::check(samples, moves, machine), samples.back().t_s};
}

TEST(CornerBlend, BlendedPolygonPassesTheCheckFaster) {
  Machine machine = default_machine();
  machine.path_tolerance_mm = 0.05;
  const RunResult sharp = run_polygon(false, machine, 36), blended = run_polygon(true, machine, 36);
  for (const auto* r : {&sharp, &blended}) {
    std::string failures;
    for (const auto& f : r->report.failures(machine)) failures += "\n  " + f;
    EXPECT_TRUE(r->report.passed(machine)) << failures;
  }
  EXPECT_EQ(sharp.report.blends, 0);
  EXPECT_EQ(blended.report.blends, 36);
  EXPECT_GT(blended.report.max_blend_deviation_mm, 0.5 * machine.path_tolerance_mm);
  EXPECT_LE(blended.report.max_blend_deviation_mm, machine.path_tolerance_mm);
  EXPECT_LT(blended.time_s, sharp.time_s);
}

TEST(CornerBlend, KeepsTheCornerWhereTheBlendWouldBeSlower) {
  // A blend of a 90 degree corner is slower than the stop (the jerk of its curvature change): kept.
  const Machine machine = default_machine();
  const RunResult r = run_polygon(true, machine);
  EXPECT_EQ(r.report.blends, 0);
  EXPECT_TRUE(r.report.passed(machine));
}

TEST(CornerBlend, CheckerRejectsABlendBeyondItsTolerance) {
  // The blend of a corner with 0.05 mm, checked against a tolerance of 0.01 mm.
  const auto out = blend_polyline({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}}, 0.05);
  ASSERT_EQ(out.size(), 3U);
  ASSERT_TRUE(out[1].corner);
  program::ProgrammedCorner pc = *out[1].corner;
  pc.tolerance_mm = 0.01;
  EXPECT_GT(verify::blend_deviation(*out[1].curve, pc), 0.04);
  std::vector<program::Move> moves = out;
  moves[1].corner = pc;
  const Machine machine = default_machine();
  const verify::Report r = verify::check(testing::plan_and_sample(machine, moves), moves, machine);
  EXPECT_FALSE(r.passed(machine));
  EXPECT_GT(r.max_blend_deviation_ratio, 4.0);
}

}  // namespace
}  // namespace kontur
