// Corner blending within the G64 tolerance (program/corner_blender.hpp): every blend within its
// tolerance of the programmed lines, curvature-continuous at both ends, none under exact stop,
// lines between blends keep a straight middle, and a blended square passes the check faster.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/piece_distance.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/program/corner_blender.hpp>
#include <kontur/tolerances.hpp>
#include <kontur/verify/checker.hpp>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/machine_limits.hpp"
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
std::vector<program::Move> blend_polyline(const std::vector<Vec3>& pts, double tol_mm, bool enabled = true,
                                          const Machine* machine = nullptr) {
  // (with a machine: each blend's shape chosen for it, as the pipeline wires the blender)
  program::CornerBlender blender = machine == nullptr
                                       ? program::CornerBlender(enabled)
                                       : program::CornerBlender(enabled, machine, [machine](const Curve& c, double f) {
                                           return plan::curve_speed_cap(c, f, *machine);
                                         });
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

// On random corners in space (lines 0.01-50 mm, tolerances 0.1 um - 0.1 mm), with the equally
// spaced quintic and with the shape chosen for a machine (when the blend pays): every blend within
// its tolerance, and most of those whose lines are long enough at it.
class CornerBlendRandom : public ::testing::TestWithParam<bool> {};

TEST_P(CornerBlendRandom, DeviationWithinToleranceOnRandomCorners) {
  Machine machine = default_machine();
  machine.servo_period_s = 0.001;
  testing::set_every_axis(machine, 203.2, 762.0, 76200.0);
  const bool shaped = GetParam();
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> len(0.01, 50.0), tol(1e-4, 0.1), coord(-500.0, 500.0);
  int blends = 0, at_tolerance = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(coord(rng), coord(rng), coord(rng));
    const Vec3 t1 = random_unit(rng), t2 = random_unit(rng);
    const double delta = tol(rng);
    const std::vector<Vec3> pts = {p - len(rng) * t1, p, p + len(rng) * t2};
    const auto out = blend_polyline(pts, delta, true, shaped ? &machine : nullptr);
    if (shaped && out.size() == 2U) continue;  // (a stop was faster: blend_pays)
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
  EXPECT_GT(blends, shaped ? 300 : 1000);
  EXPECT_GT(at_tolerance, 100);  // where the lines are long enough, the blend uses its tolerance
}

std::string shape_name(const ::testing::TestParamInfo<bool>& shaped) {
  return shaped.param ? "Shaped" : "EquallySpaced";
}
INSTANTIATE_TEST_SUITE_P(EqualAndShaped, CornerBlendRandom, ::testing::Bool(), shape_name);

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

// Found by the Haas 4-axis corpus program once blends paid there: the blend moves had the extra
// axes at zero, so A jumped from 10 degrees to 0 and back at every blended corner.
TEST(CornerBlend, ABlendKeepsTheExtraAxesWhereBothMovesHaveThem) {
  ExtraAxes at{};
  at[0] = 10.0;  // A [deg]
  at[4] = -2.5;  // V [mm]
  program::CornerBlender blender(true);
  std::vector<program::Move> out;
  for (const auto& [a, b] : {std::pair{Vec3(0, 0, 0), Vec3(10, 0, 0)}, std::pair{Vec3(10, 0, 0), Vec3(10, 10, 0)}}) {
    program::Move m = line_move(a, b, 0.05);
    m.extra_start = m.extra_end = at;
    blender.push(m, out);
  }
  blender.flush(out);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_TRUE(out[1].corner.has_value());
  for (const program::Move& m : out) {
    EXPECT_EQ(m.extra_start, at);
    EXPECT_EQ(m.extra_end, at);
  }
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

// Every shape of the blender's family (corner_blend_shape): the blend starts and ends exactly on
// its lines (P - d t1, P + d t2), with B' and B'' along them (zero curvature), its middle is where
// the control points put it, and its derivatives are the curve's (central differences).
TEST(CornerBlend, AnyShapeOfTheFamilyStartsAndEndsOnItsLinesWithZeroCurvature) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> third(tolerances::blend_shape_third_min, tolerances::blend_shape_third_max),
      trim(1e-3, 20.0), unit(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const Vec3 p = 300.0 * random_unit(rng);
    const Vec3 t1 = random_unit(rng), t2 = random_unit(rng);
    const double d = trim(rng);
    const CornerBlendShape shape = corner_blend_shape(third(rng));
    const CornerBlendCurve c(p, t1, t2, d, shape);
    const Derivatives d0 = c.derivatives(0.0, 3), d1 = c.derivatives(1.0, 3);
    EXPECT_EQ(d0[0], Vec3(p - d * t1));
    EXPECT_EQ(d1[0], Vec3(p + d * t2));
    for (const auto& [dd, t] : {std::pair{d0, t1}, std::pair{d1, t2}}) {
      EXPECT_LT((dd[1].normalized() - t).norm(), 1e-12);
      EXPECT_LT(dd[1].cross(dd[2]).norm() / std::pow(dd[1].norm(), 3), 1e-9 / d);  // curvature [1/mm]
    }
    const Vec3 middle = p + (1.0 + 5.0 * shape.second + 10.0 * shape.third) / 32.0 * d * (t2 - t1);
    EXPECT_LT((c.point(0.5) - middle).norm(), 1e-12 * (d + p.norm()));
    const double u = 0.01 + 0.98 * unit(rng), h = 1e-5;
    const Derivatives at = c.derivatives(u, 3), before = c.derivatives(u - h, 3), after = c.derivatives(u + h, 3);
    for (int k = 0; k < 3; ++k)
      EXPECT_LT((at[k + 1] - (after[k] - before[k]) / (2.0 * h)).norm(), 1e-6 * (1.0 + at[k + 1].norm())) << k;
  }
}

// The blender sizes each shape of the family to the tolerance and takes the one that passes the
// corner fastest. Against the quintic with equally spaced control points (the blend until
// 2026-12-05) sized the same way: within the tolerance, never a lower speed cap, and on a machine
// whose jerk is its acceleration per 0.01 s (a LinuxCNC INI without MAX_JERK) about 1.9 times its
// cap at a turn of 4.5 degrees (whose curvature rose from the lines over a sixth of the blend:
// sam-circle_lines, a spiral of 370 such corners, took 12.9 s on XYZ.ini, now 8.2 s).
TEST(CornerBlend, TheShapeChosenForTheMachinePassesACornerAtLeastAsFastAsEquallySpacedControlPoints) {
  Machine soft = default_machine(), stiff = default_machine();
  soft.servo_period_s = stiff.servo_period_s = 0.001;
  testing::set_every_axis(soft, 203.2, 762.0, 76200.0);    // jerk A / 0.01 s
  testing::set_every_axis(stiff, 203.2, 762.0, 762000.0);  // jerk A / T
  const double tol_mm = 0.01, feed_mm_s = 200.0;
  int blends = 0;
  for (const Machine* m : {&soft, &stiff}) {
    const auto speed = [m](const Curve& c, double f) { return plan::curve_speed_cap(c, f, *m); };
    for (const double turn_deg : {2.0, 4.5, 15.0, 45.0, 90.0, 120.0}) {
      SCOPED_TRACE(std::to_string(turn_deg) + " degrees, jerk " + std::to_string(m->axes[0].max_jerk));
      const double a = turn_deg * M_PI / 180.0;
      const Vec3 t1 = Vec3::UnitX(), t2(std::cos(a), std::sin(a), 0.0);
      program::CornerBlender blender(true, m, speed);
      std::vector<program::Move> out;
      blender.push(line_move(-20.0 * t1, Vec3::Zero(), tol_mm, feed_mm_s), out);
      blender.push(line_move(Vec3::Zero(), 20.0 * t2, tol_mm, feed_mm_s), out);
      blender.flush(out);
      if (out.size() != 3U) continue;  // (a stop is faster than any blend: blend_pays)
      ++blends;
      const Curve& chosen = *out[1].curve;
      EXPECT_LE(verify::blend_deviation(chosen, *out[1].corner), tol_mm * (1.0 + 1e-9));
      const double d_equal = tolerances::blend_tolerance_share * tol_mm / unit_blend_deviation(t1, t2);
      const CornerBlendCurve equal(Vec3::Zero(), t1, t2, d_equal);
      const double v_chosen = speed(chosen, feed_mm_s), v_equal = speed(equal, feed_mm_s);
      EXPECT_GE(v_chosen, 0.999 * v_equal);
      if (m == &soft && turn_deg == 4.5) {
        EXPECT_GT(v_chosen, 1.7 * v_equal);
      }
    }
  }
  EXPECT_GE(blends, 6);  // (7 of the 12 corners blend)
}

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

// ---- junctions with arcs (a TransitionCurve between the trimmed moves)

// A chain of lines and arcs in space from the origin: each piece starts where the last ended,
// tangent to it or turned by up to 60 degrees; arcs of radius 0.5-20 mm in a random plane through
// the direction, sweeping 0.2-2.5 rad. The tolerance `tol_mm` at every junction.
std::vector<program::Move> line_arc_chain(std::mt19937_64& rng, int pieces, double tol_mm, double feed_mm_s = 100.0) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Vec3 p = Vec3::Zero(), t = Vec3::UnitX();
  std::vector<program::Move> moves;
  for (int i = 0; i < pieces; ++i) {
    if (unit(rng) < 0.5) {  // a corner: t turned about a random normal
      const Vec3 axis = t.cross(random_unit(rng)).normalized();
      t = Eigen::AngleAxisd(unit(rng) * M_PI / 3.0, axis) * t;
    }
    std::shared_ptr<const Curve> c;
    if (unit(rng) < 0.4) {
      c = std::make_shared<const LineSegment>(p, p + (0.5 + 5.0 * unit(rng)) * t);
    } else {
      const Vec3 n = t.cross(random_unit(rng)).normalized();
      const double r = 0.5 + 19.5 * unit(rng);
      CircleFrame f;
      f.normal = n;
      f.e1 = t.cross(n);  // e2 = n x e1 = t: the arc starts along t
      f.e2 = n.cross(f.e1);
      f.centre = p - r * f.e1;
      c = std::make_shared<const HelixArc>(f, r, 0.2 + 2.3 * unit(rng));
    }
    program::Move m = program::move_along(c, feed_mm_s, false, i + 1);
    m.corner_tolerance_mm = tol_mm;
    const Derivatives e = c->derivatives(c->u_max(), 1);
    p = e[0];
    t = e[1].normalized();
    moves.push_back(std::move(m));
  }
  return moves;
}

std::vector<program::Move> blend_moves(const std::vector<program::Move>& moves, const Machine* machine = nullptr) {
  program::CornerBlender blender =
      machine
          ? program::CornerBlender(
                true, machine,
                [machine](const Curve& c, double feed_mm_s) { return plan::curve_speed_cap(c, feed_mm_s, *machine); },
                [machine](const Derivatives& a, const Derivatives& b) {
                  const plan::Junction j = plan::junction(a, b, *machine);
                  return program::JunctionPass{j.velocity, j.jerk_share};
                })
          : program::CornerBlender(true);
  std::vector<program::Move> out;
  for (const program::Move& m : moves) blender.push(m, out);
  blender.flush(out);
  return out;
}

TEST(CornerBlend, JunctionsWithArcsBlendCurvatureContinuousWithinTheTolerance) {
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> tol(1e-3, 0.1);
  int blends = 0, at_tolerance = 0, tangent = 0;
  for (int chain = 0; chain < 60; ++chain) {
    const double delta = tol(rng);
    const std::vector<program::Move> moves = line_arc_chain(rng, 12, delta);
    const std::vector<program::Move> out = blend_moves(moves);
    // The path runs from the first programmed point to the last without a gap.
    EXPECT_LT((out.front().curve->point(out.front().curve->u_min()) - Vec3::Zero()).norm(), 1e-12);
    const Curve& last = *moves.back().curve;
    EXPECT_LT((out.back().curve->point(out.back().curve->u_max()) - last.point(last.u_max())).norm(), 1e-12);
    for (std::size_t i = 0; i + 1 < out.size(); ++i) {
      const Curve &a = *out[i].curve, &b = *out[i + 1].curve;
      EXPECT_LT((a.point(a.u_max()) - b.point(b.u_min())).norm(), 1e-9) << "chain " << chain << " move " << i;
      EXPECT_GT(out[i].length_mm, 0.0);
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (!out[i].corner) continue;
      const double dev = verify::blend_deviation(*out[i].curve, *out[i].corner);
      EXPECT_LE(dev, delta * (1 + 1e-9)) << "chain " << chain << " move " << i;
      if (dynamic_cast<const CornerBlendCurve*>(out[i].curve.get()) != nullptr) continue;  // two lines: tests above
      ++blends;
      if (dev >= 0.5 * delta) ++at_tolerance;
      // Tangent and curvature-continuous with the trimmed moves on both sides.
      ASSERT_TRUE(i > 0 && i + 1 < out.size());
      const Curve &before = *out[i - 1].curve, &blend = *out[i].curve, &after = *out[i + 1].curve;
      for (const auto& [x, y] : {std::pair{curve_end(before, before.u_max(), true), curve_end(blend, 0.0, false)},
                                 std::pair{curve_end(blend, 1.0, true), curve_end(after, after.u_min(), false)}}) {
        EXPECT_LT((x.point - y.point).norm(), 1e-9);
        EXPECT_LT((x.tangent - y.tangent).norm(), 1e-9);
        EXPECT_LT((x.curvature - y.curvature).norm(), 1e-7 * std::max(1.0, x.curvature.norm()));
      }
      const Curve& programmed_in = *out[i].corner->before;
      if ((curve_end(programmed_in, programmed_in.u_max(), true).tangent -
           curve_end(*out[i].corner->after, 0.0, false).tangent)
              .norm() < 1e-9)
        ++tangent;
    }
  }
  EXPECT_GT(blends, 300);
  EXPECT_GT(tangent, 50);        // tangent junctions with a jump of curvature are blended too
  EXPECT_GT(at_tolerance, 100);  // where the moves are long enough, the blend uses its tolerance
}

TEST(CornerBlend, ArcBlendsPassTheCheckAndRunFasterThanTheirJunctions) {
  // Lines of 30 mm joined by half circles of radius 3 mm (tangent: only the curvature jumps, by
  // 1/3 per mm), and the same with every piece turned by 20 degrees against the last.
  Machine machine = default_machine();
  machine.path_tolerance_mm = 0.02;
  for (const double kink_deg : {0.0, 20.0}) {
    std::vector<program::Move> moves;
    Vec3 p = Vec3::Zero(), t = Vec3::UnitX();
    for (int i = 0; i < 8; ++i) {
      t = Eigen::AngleAxisd(kink_deg * M_PI / 180.0, Vec3::UnitZ()) * t;
      std::shared_ptr<const Curve> c;
      if (i % 2 == 0) {
        c = std::make_shared<const LineSegment>(p, p + 30.0 * t);
      } else {
        CircleFrame f;
        f.normal = Vec3::UnitZ();
        f.e1 = t.cross(f.normal);
        f.e2 = f.normal.cross(f.e1);
        f.centre = p - 3.0 * f.e1;
        c = std::make_shared<const HelixArc>(f, 3.0, M_PI);
      }
      program::Move m = program::move_along(c, 150.0, false, i + 1);
      m.corner_tolerance_mm = machine.path_tolerance_mm;
      p = c->point(c->u_max());
      t = c->derivatives(c->u_max(), 1)[1].normalized();
      moves.push_back(std::move(m));
    }
    std::vector<program::Move> blended = blend_moves(moves, &machine);
    const auto run = [&](std::vector<program::Move>& ms) {
      const std::vector<verify::Sample> samples = testing::plan_and_sample(machine, ms);
      for (std::size_t i = 0; i < ms.size(); ++i) ms[i].id = static_cast<program::MoveId>(i);
      return RunResult{verify::check(samples, ms, machine), samples.back().t_s};
    };
    const RunResult sharp = run(moves), smooth = run(blended);
    for (const auto* r : {&sharp, &smooth}) {
      std::string failures;
      for (const auto& f : r->report.failures(machine)) failures += "\n  " + f;
      EXPECT_TRUE(r->report.passed(machine)) << kink_deg << " degrees" << failures;
    }
    // Tangent junctions lose only their jump of curvature: every one is blended, much faster. A
    // corner of 20 degrees blended within 0.02 mm is still a slow turn, about as fast as the near
    // stop (1 % faster): the blender may take either (TheBlenderChoosesTheFasterOfBlendAndJunction).
    if (kink_deg == 0.0) {
      EXPECT_EQ(smooth.report.blends, 7);
      EXPECT_LT(smooth.time_s, 0.9 * sharp.time_s) << sharp.time_s;
    } else {
      EXPECT_LE(smooth.time_s, 1.02 * sharp.time_s) << sharp.time_s;
    }
    EXPECT_LE(smooth.report.max_blend_deviation_mm, machine.path_tolerance_mm);
  }
}

// The machining time [s] of the moves, planned, sampled and checked (the check must pass).
double checked_time(const Machine& machine, std::vector<program::Move> ms) {
  const std::vector<verify::Sample> samples = testing::plan_and_sample(machine, ms);
  for (std::size_t i = 0; i < ms.size(); ++i) ms[i].id = static_cast<program::MoveId>(i);
  const verify::Report report = verify::check(samples, ms, machine);
  EXPECT_TRUE(report.passed(machine));
  return samples.back().t_s;
}

// The blender blends a junction only where its estimate says the blend is faster than passing
// the junction as it is (a stop at a corner). Its choice, against both: a line meeting a line at
// a corner, or a half circle tangentially or at a kink, on the default machine and on one whose
// jerk is A / T (each jerk ramp a servo period long: stops cost little more than the speed
// change itself, so the estimate must count the acceleration, not only the jerk).
TEST(CornerBlend, TheBlenderChoosesTheFasterOfBlendAndJunction) {
  Machine soft = default_machine(), stiff = default_machine();
  for (AxisLimits& a : stiff.axes) a.max_jerk = a.max_acceleration / stiff.servo_period_s;
  int cases = 0, blended = 0, kept = 0;
  for (const Machine* machine : {&soft, &stiff}) {
    for (const double tol_mm : {0.01, 0.1}) {
      for (const double turn_deg : {0.0, 20.0, 45.0, 90.0, 120.0}) {
        for (const bool arc : {false, true}) {
          if (!arc && turn_deg == 0.0) continue;  // two collinear lines: no corner
          const Vec3 t = Eigen::AngleAxisd(turn_deg * M_PI / 180.0, Vec3::UnitZ()) * Vec3::UnitX();
          std::shared_ptr<const Curve> second;
          if (arc) {
            CircleFrame f;
            f.normal = Vec3::UnitZ();
            f.e1 = t.cross(f.normal);
            f.e2 = f.normal.cross(f.e1);
            f.centre = Vec3(10.0, 0.0, 0.0) - 3.0 * f.e1;
            second = std::make_shared<const HelixArc>(f, 3.0, M_PI);
          } else {
            second = std::make_shared<const LineSegment>(Vec3(10.0, 0.0, 0.0), Vec3(10.0, 0.0, 0.0) + 10.0 * t);
          }
          std::vector<program::Move> moves{line_move(Vec3::Zero(), Vec3(10.0, 0.0, 0.0), tol_mm, 150.0, false, 1),
                                           program::move_along(second, 150.0, false, 2)};
          moves[1].corner_tolerance_mm = tol_mm;
          const std::vector<program::Move> chosen = blend_moves(moves, machine), forced = blend_moves(moves);
          const double t_chosen = checked_time(*machine, chosen), t_forced = checked_time(*machine, forced),
                       t_kept = checked_time(*machine, moves);
          ASSERT_EQ(forced.size(), 3u) << turn_deg << " degrees, arc " << arc;  // the blend is possible
          ++cases;
          (chosen.size() == 3u ? blended : kept) += 1;
          // (the estimate is an estimate: within 5 % of the better choice; until 2026-12-04 it refused
          // blends 4-25 % faster here: a tangent arc on the soft machine, 20 and 45 degrees on the
          // stiff. Since 2026-12-06 a half circle alone after a stop takes the 0.97 centripetal
          // share: kept, the 120-degree junction into it on the stiff machine at 0.1 mm runs 0.315 s,
          // blended 0.332 s, and the estimate, which sees the arc at the chain's share, blends it)
          EXPECT_LE(t_chosen, 1.05 * std::min(t_forced, t_kept))
              << (machine == &stiff ? "stiff" : "soft") << " machine, tolerance " << tol_mm << " mm, turn " << turn_deg
              << " degrees, arc " << arc << ": chosen " << t_chosen << " s, blended " << t_forced << " s, kept "
              << t_kept << " s";
        }
      }
    }
  }
  EXPECT_EQ(cases, 36);
  EXPECT_GT(blended, 5);  // both choices are made
  EXPECT_GT(kept, 5);
}

// LinuxCNC's short_segments_0.001: straight runs of 25 um lines meeting at right angles. A blend
// there trims 11 um and runs at about 1 mm/s; timed over half of each tiny line it looked 5 %
// faster than the stop, and was 13 ms slower at each corner: the corner is approached along the
// whole straight run, which the estimate now times (Held::straight_before_mm).
TEST(CornerBlend, ACornerAtTheEndOfAStraightRunOfTinyLinesIsTimedAlongTheRun) {
  const Machine machine = default_machine();
  std::vector<program::Move> moves;
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < 400; ++i) {
    const Vec3 q = p + 0.0254 * (i < 200 ? Vec3::UnitX() : Vec3::UnitZ());
    moves.push_back(line_move(p, q, 0.01, 400.0, false, i + 1));
    p = q;
  }
  const double t_chosen = checked_time(machine, blend_moves(moves, &machine)),
               t_forced = checked_time(machine, blend_moves(moves)), t_kept = checked_time(machine, moves);
  EXPECT_GT(t_forced, t_kept);  // the blend is the slower choice here ...
  EXPECT_EQ(t_chosen, t_kept) << "blended " << t_forced << " s";  // ... and is not taken
}

TEST(CornerBlend, CheckerMeasuresAnArcBlendAgainstTheProgrammedArc) {
  // A line into a tangent quarter circle of radius 2 mm, blended with 0.01 mm: the checker's
  // deviation equals the largest distance by brute force (401 points of the blend, 20,001 of each programmed piece),
  // and the same blend judged against the arc moved by 0.03 mm is beyond its tolerance.
  CircleFrame f;
  f.e1 = -Vec3::UnitY();
  f.e2 = Vec3::UnitX();
  f.normal = Vec3::UnitZ();
  f.centre = Vec3(10.0, 2.0, 0.0);
  const auto line = std::make_shared<const LineSegment>(Vec3::Zero(), Vec3(10.0, 0.0, 0.0));
  const auto arc = std::make_shared<const HelixArc>(f, 2.0, M_PI / 2.0);
  std::vector<program::Move> moves = {program::move_along(line, 100.0, false, 1),
                                      program::move_along(arc, 100.0, false, 2)};
  for (auto& m : moves) m.corner_tolerance_mm = 0.01;
  const auto out = blend_moves(moves);
  ASSERT_EQ(out.size(), 3U);
  ASSERT_TRUE(out[1].corner);
  const program::ProgrammedCorner& pc = *out[1].corner;
  const double dev = verify::blend_deviation(*out[1].curve, pc);
  double brute = 0.0;
  for (int k = 0; k <= 400; ++k) {
    const Vec3 q = out[1].curve->point(k / 400.0);
    double nearest = std::numeric_limits<double>::infinity();
    for (const Curve* piece : {pc.before.get(), pc.after.get()})
      for (int j = 0; j <= 20000; ++j) {
        const double u = piece->u_min() + (piece->u_max() - piece->u_min()) * j / 20000.0;
        nearest = std::min(nearest, (piece->point(u) - q).norm());
      }
    brute = std::max(brute, nearest);
  }
  EXPECT_NEAR(dev, brute, 1e-6);
  EXPECT_GT(dev, 0.005);
  EXPECT_LE(dev, 0.01);
  program::ProgrammedCorner moved = pc;
  CircleFrame g = f;
  g.centre += Vec3(0.0, 0.03, 0.0);
  moved.after =
      std::make_shared<const CurvePiece>(std::make_shared<const HelixArc>(g, 2.0, M_PI / 2.0), 0.0, pc.after->u_max());
  const Vec3 shift(0.0, 0.03, 0.0);
  moved.before = std::make_shared<const LineSegment>(pc.before->point(pc.before->u_min()) + shift,
                                                     pc.before->point(pc.before->u_max()) + shift);
  EXPECT_GT(verify::blend_deviation(*out[1].curve, moved), 0.015);
}

// A random right-handed circle frame, its centre within 50 mm of the origin (draws: the normal, a
// direction for e1, the centre).
CircleFrame random_circle_frame(std::mt19937_64& rng) {
  CircleFrame f;
  f.normal = random_unit(rng);
  f.e1 = f.normal.cross(random_unit(rng)).normalized();
  f.e2 = f.normal.cross(f.e1);
  f.centre = 50.0 * random_unit(rng);
  return f;
}

// The distance [mm] from p to the part [u0, u1] of `arc` by brute force: the nearest of 20,001
// points, refined by a golden-section search between its neighbours.
double nearest_by_sampling(const HelixArc& arc, const Vec3& p, double u0, double u1) {
  const auto dist = [&](double v) { return (arc.point(v) - p).norm(); };
  const double h = (u1 - u0) / 20000.0;
  int best_j = 0;
  for (int j = 1; j <= 20000; ++j)
    if (dist(u0 + h * j) < dist(u0 + h * best_j)) best_j = j;
  return std::min(dist(u0 + h * best_j),
                  golden_section_minimum(dist, std::max(u0, u0 + h * (best_j - 1)),
                                         std::min(u1, u0 + h * (best_j + 1)), 200)
                      .second);
}

// On a slight spiral distance_mm (d) is never below the nearest point's distance and above it by at
// most sqrt(1 + s^2 R / rho) (s the radius change per radian over the radius, R at most r_max,
// rho p's distance from the axis).
void expect_within_slight_spiral_bound(const HelixArc& arc, const Vec3& p, double d, double nearest, double r_max) {
  const CircleFrame& f = arc.frame();
  const double slope = std::abs(arc.radius_change_mm()) / (arc.radius_mm() * arc.sweep_rad());
  const Vec3 q = p - f.centre;
  const double rho = (q - q.dot(f.normal) * f.normal).norm();
  EXPECT_GE(d, nearest - 1e-9);
  EXPECT_LE(d, nearest * std::sqrt(1.0 + slope * slope * r_max / rho) + 1e-9);
}

TEST(HelixArcDistance, EqualsTheNearestOfDenseSamplesOnCirclesHelicesAndSpirals) {
  // Seeded arcs (a third circles, a third helices, a third with a change of radius), a random part
  // [u0, u1] of each, points within 1 mm of the part and beyond its ends: distance_mm equals the
  // nearest point found by dense sampling and a golden-section search, to 1e-9 mm on circles (where
  // it is exact) and 1e-7 mm on the others (but slight spirals: within their bound).
  std::mt19937_64 rng(412);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 60; ++i) {
    const CircleFrame f = random_circle_frame(rng);
    const double r = 0.5 + 20.0 * unit(rng);
    const int kind = i % 3;
    // (helices of up to 2.5 turns)
    const HelixArc arc(f, r, 0.2 + (kind == 1 ? 15.0 : 6.0) * unit(rng), kind == 1 ? 20.0 * (unit(rng) - 0.5) : 0.0,
                       kind == 2 ? 0.2 * r * (unit(rng) - 0.5) : 0.0);
    const double u0 = 0.5 * unit(rng), u1 = u0 + (1.0 - u0) * (0.05 + 0.95 * unit(rng));
    for (int k = 0; k < 20; ++k) {
      const double u = u0 + (u1 - u0) * (1.4 * unit(rng) - 0.2);
      const Vec3 p = arc.point(std::clamp(u, 0.0, 1.0)) + unit(rng) * random_unit(rng);
      const double brute = nearest_by_sampling(arc, p, u0, u1);
      // (a slight spiral: the point at p's angle, OnASlightSpiralIsThePointAtTheSameAngle... below)
      const double slope = std::abs(arc.radius_change_mm()) / (r * arc.sweep_rad());
      if (kind == 2 && slope <= tolerances::arc_slight_spiral_slope) {
        expect_within_slight_spiral_bound(arc, p, arc.distance_mm(p, u0, u1), brute, 1.1 * r);
        continue;
      }
      EXPECT_NEAR(arc.distance_mm(p, u0, u1), brute, kind == 0 ? 1e-9 + 1e-8 * r : 1e-7 + 1e-8 * r)
          << "arc " << i << " point " << k;
    }
  }
}

// The cheap lower bound of an arc's distance (the ring that holds the part's points) is never above
// the nearest point's distance, and equals it on a circle where p's angle lies within the part; so
// nearer_distance, which leaves out the farther piece where its bound rules it out, returns exactly
// std::min of both distances: for a line and an arc, two arcs (circles, helices, spirals), and an
// arc and another curve (no bound), points near either piece and between them.
TEST(HelixArcDistance, TheLowerBoundHoldsAndTheNearerOfTwoPiecesIsExactlyTheSmallerDistance) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int left_out = 0;
  for (int i = 0; i < 60; ++i) {
    const CircleFrame f = random_circle_frame(rng);
    const double r = 0.5 + 20.0 * unit(rng);
    const int kind = i % 3;
    const auto arc = std::make_shared<const HelixArc>(
        f, r, 0.2 + 6.0 * unit(rng), kind == 1 ? 10.0 * (unit(rng) - 0.5) : 0.0,
        kind == 2 ? 0.2 * r * (unit(rng) - 0.5) : 0.0);
    const double u0 = 0.5 * unit(rng), u1 = u0 + (1.0 - u0) * (0.05 + 0.95 * unit(rng));
    const CurvePiece part(arc, u0, u1);
    const Vec3 end = arc->point(u1), tangent = arc->derivatives(u1, 1)[1].normalized();
    const LineSegment line(end, end + (0.5 + 5.0 * unit(rng)) * (tangent + 0.5 * random_unit(rng)).normalized());
    const auto other_arc = std::make_shared<const HelixArc>(random_circle_frame(rng), 0.5 + 10.0 * unit(rng),
                                                            0.2 + 3.0 * unit(rng), kind == 0 ? 0.0 : 2.0 * unit(rng));
    const CornerBlendCurve generic(end, tangent, random_unit(rng), 1.0 + unit(rng), corner_blend_shape(0.5));
    const PieceDistance to_part(part), to_line(line), to_other(*other_arc), to_generic(generic);
    for (int k = 0; k < 40; ++k) {
      const double u = u0 + (u1 - u0) * (1.4 * unit(rng) - 0.2);
      const Vec3 p = arc->point(std::clamp(u, 0.0, 1.0)) + 2.0 * unit(rng) * random_unit(rng);
      const double d = to_part(p), bound = to_part.lower_bound(p);
      EXPECT_LE(bound, nearest_by_sampling(*arc, p, u0, u1) + 1e-9) << "arc " << i << " point " << k;
      if (kind == 0) {
        const Vec3 q = p - f.centre;
        // (p's angle from e1 in [0, 2 pi), the part's from a0 to a1 <= 6.4 rad)
        double angle = std::atan2(q.dot(f.e2), q.dot(f.e1));
        if (angle < 0.0) angle += 2.0 * std::numbers::pi;
        const double a0 = arc->sweep_rad() * u0, a1 = arc->sweep_rad() * u1;
        const bool within = (angle >= a0 && angle <= a1) || angle + 2.0 * std::numbers::pi <= a1;
        if (within) {
          EXPECT_NEAR(bound, d, 1e-12 * (1.0 + r)) << "arc " << i << " point " << k;
        }
      }
      for (const PieceDistance* other : {&to_line, &to_other, &to_generic}) {
        const double exact = std::min(d, (*other)(p));
        EXPECT_EQ(nearer_distance(to_part, *other, p), exact) << "arc " << i << " point " << k;
        EXPECT_EQ(nearer_distance(*other, to_part, p), exact) << "arc " << i << " point " << k;
        if (std::max(bound, other->lower_bound(p)) > exact * (1.0 + 1e-6) + 1e-6) ++left_out;
      }
    }
  }
  EXPECT_GT(left_out, 500);  // (the bound does leave distances out)
}

// On a helix of several turns (thread milling) and a spiral with rise, the nearest point may lie on
// any turn: distance_mm equals the brute-force nearest to 1e-7 mm, also for points between turns
// and near the axis. (Newton's method from the nearest of 8 samples a turn stepped onto another
// turn: 2.26 mm where the nearest point lay 0.396 mm away.)
TEST(HelixArcDistance, OnAHelixOfSeveralTurnsIsTheDistanceToTheNearestTurn) {
  std::mt19937_64 rng(65);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int off_their_point = 0;  // points nearer another point than the one they were drawn from
  for (int i = 0; i < 80; ++i) {
    const CircleFrame f = random_circle_frame(rng);
    const double r = 0.5 + 10.0 * unit(rng), turns = 1.0 + 5.0 * unit(rng);
    const double sweep = 2.0 * M_PI * turns, pitch = (0.05 + 2.0 * unit(rng)) * r;  // [mm] a turn
    // (helices, spirals with rise, and spirals with rise slight over 2 rad as rgh's ramps)
    const double dr = i % 3 == 0 ? 0.0
                      : i % 3 == 1 ? 0.5 * r * (unit(rng) - 0.5)
                                   : 2.0 * tolerances::arc_slight_spiral_slope * r * 2.0 * (unit(rng) - 0.5);
    const HelixArc arc(f, r, sweep, pitch * turns, dr);
    const double u0 = 0.2 * unit(rng), u1 = 1.0 - 0.2 * unit(rng);
    for (int k = 0; k < 20; ++k) {
      const double u = u0 + (u1 - u0) * unit(rng);
      // (toward the axis or outward, and along it up to a pitch)
      const Vec3 radial = (arc.point(u) - f.centre - (arc.point(u) - f.centre).dot(f.normal) * f.normal).normalized();
      const Vec3 p = arc.point(u) + r * (1.6 * unit(rng) - 1.0) * radial + pitch * (unit(rng) - 0.5) * f.normal;
      const double brute = nearest_by_sampling(arc, p, u0, u1);
      const double d = arc.distance_mm(p, u0, u1);
      EXPECT_NEAR(d, brute, 1e-7 + 1e-8 * r) << "helix " << i << " point " << k;
      off_their_point += brute + 1e-6 < (arc.point(u) - p).norm() ? 1 : 0;
    }
  }
  EXPECT_GT(off_their_point, 100);  // (the points test more than the turn they were drawn on)
}

// On a slight spiral (an arc whose programmed end lay off its circle, its radius changing by at
// most tolerances::arc_slight_spiral_slope of it per radian) distance_mm is the distance to the
// point at p's angle: never below the nearest point's (dense samples and a golden-section search),
// and above it by at most the factor sqrt(1 + s^2 R / rho) (s the slope, rho p's distance from
// the axis), which near the arc is 1 + s^2 / 2 (4.5e-4 at the largest slope). Newton's method there
// took three fifths of rgh's run (its arcs of 0.23 mm change by up to 0.02 per radian).
TEST(HelixArcDistance, OnASlightSpiralIsThePointAtTheSameAngleAboveTheNearestByAtMostItsSlope) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int above = 0;  // distances measurably above the nearest
  for (int i = 0; i < 40; ++i) {
    const CircleFrame f = random_circle_frame(rng);
    const double r = 0.2 + 20.0 * unit(rng), sweep = 0.2 + 6.0 * unit(rng);
    const double dr = 2.0 * tolerances::arc_slight_spiral_slope * r * sweep * (unit(rng) - 0.5);
    const HelixArc arc(f, r, sweep, 0.0, dr);
    const double u0 = 0.5 * unit(rng), u1 = u0 + (1.0 - u0) * (0.05 + 0.95 * unit(rng));
    for (int k = 0; k < 20; ++k) {
      const double u = u0 + (u1 - u0) * (1.4 * unit(rng) - 0.2);
      const Vec3 p = arc.point(std::clamp(u, 0.0, 1.0)) + std::min(1.0, 0.5 * r) * unit(rng) * random_unit(rng);
      const double brute = nearest_by_sampling(arc, p, u0, u1);
      const double d = arc.distance_mm(p, u0, u1);
      expect_within_slight_spiral_bound(arc, p, d, brute, r + std::abs(dr));
      above += d > brute + 1e-9 ? 1 : 0;
    }
  }
  EXPECT_GT(above, 0);  // (the bound is looked at, not only exact cases)
}

}  // namespace
}  // namespace kontur
