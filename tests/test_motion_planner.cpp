// Moves to setpoints: the limits hold on the setpoints themselves (finite differences), the path
// is continuous, corners are slow, tangent junctions are not, and the end is reached exactly.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/geometry/transition_curve.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <numbers>
#include <random>

#include "support/planner_run.hpp"
#include "support/machine_limits.hpp"

namespace kontur::plan {
namespace {

using program::Move;
using trajectory::Setpoint;

struct RunResult {
  std::vector<Setpoint> points;
};

RunResult run(const Machine& m, const std::vector<Move>& moves) {
  testing::PlannerRun p(m);
  RunResult r;
  for (const auto& mv : moves) {
    p.planner.push(mv);
    p.drain(r.points);
  }
  p.planner.finish();
  p.drain(r.points);
  EXPECT_TRUE(p.sampler.done());
  return r;
}

// Largest per-axis velocity, acceleration and jerk of the setpoints (backward differences),
// relative to the machine's limits; 1 means at the limit.
struct Usage {
  double v = 0, a = 0, j = 0;
};
Usage usage(const RunResult& r, const Machine& m) {
  Usage u;
  const double T = m.servo_period_s;
  const auto& p = r.points;
  for (std::size_t k = 3; k < p.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const AxisLimits& ax = m.axes[static_cast<std::size_t>(i)];
      const double x0 = p[k].position[i], x1 = p[k - 1].position[i], x2 = p[k - 2].position[i],
                   x3 = p[k - 3].position[i];
      u.v = std::max(u.v, std::abs(x0 - x1) / T / ax.max_velocity);
      u.a = std::max(u.a, std::abs(x0 - 2 * x1 + x2) / (T * T) / ax.max_acceleration);
      u.j = std::max(u.j, std::abs(x0 - 3 * x1 + 3 * x2 - x3) / (T * T * T) / ax.max_jerk);
    }
  }
  return u;
}

Move line(Vec3 a, Vec3 b, double feed, long line_no = 0) {
  return program::move_along(std::make_shared<LineSegment>(a, b), feed, false, line_no);
}

TEST(MotionPlanner, SingleLineStartsAndEndsAtRestAtTheEndPoints) {
  const Machine m = default_machine();
  const RunResult r = run(m, {line({0, 0, 0}, {100, 0, 0}, 50.0, 7)});
  ASSERT_GT(r.points.size(), 100u);
  EXPECT_EQ(r.points.front().position, Vec3(0, 0, 0));
  EXPECT_EQ(r.points.back().position, Vec3(100, 0, 0));
  EXPECT_EQ(r.points.back().v_mm_s, 0.0);
  EXPECT_EQ(r.points.front().source_line, 7);
  double vmax = 0;
  for (const auto& p : r.points) vmax = std::max(vmax, p.v_mm_s);
  EXPECT_NEAR(vmax, 50.0, 1e-9);
  // Rest-to-rest with the speed reached: T = h / v + v / a + a / j (+ at most one period).
  const double expected = 100.0 / 50 + 50.0 / 2000 + 2000.0 / 50000;
  EXPECT_NEAR(r.points.back().t_s, expected, m.servo_period_s * 1.01);
  const Usage u = usage(r, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
}

TEST(MotionPlanner, SquareCornersAreTakenWithinTheLimits) {
  const Machine m = default_machine();
  const double F = 150.0;
  const RunResult r = run(m, {line({0, 0, 0}, {50, 0, 0}, F), line({50, 0, 0}, {50, 50, 0}, F),
                              line({50, 50, 0}, {0, 50, 0}, F), line({0, 50, 0}, {0, 0, 0}, F)});
  const Usage u = usage(r, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
  // Each corner is passed: some setpoint within a hair of it, at a crawl.
  for (const Vec3& corner : {Vec3(50, 0, 0), Vec3(50, 50, 0), Vec3(0, 50, 0)}) {
    double best = 1e9, v_there = 0;
    for (const auto& p : r.points)
      if ((p.position - corner).norm() < best) {
        best = (p.position - corner).norm();
        v_there = p.v_mm_s;
      }
    EXPECT_LT(best, 1e-3);
    EXPECT_LT(v_there, 1.0);
  }
  EXPECT_EQ(r.points.back().position, Vec3(0, 0, 0));
}

// A 90 degree corner between two lines blended over 10 mm, at a feed above every cap on the blend,
// on a machine with jerk = A / T (the centripetal term sets the caps; with less jerk the curvature
// change at the blend's ends may cap them lower than its apex). run_checked plans line, blend, line
// and checks every axis's limits on the setpoints.
struct CornerBlendRun {
  Machine m = [] {
    Machine machine = default_machine();
    testing::set_every_axis(machine, 500.0, 1000.0, 1000.0 / machine.servo_period_s);
    return machine;
  }();
  double F = 400.0;                        // [mm/s]
  Vec3 corner{100, 0, 0}, t1{1, 0, 0}, t2{0, 1, 0};
  double d = 10.0;                         // [mm] trimmed on each line
  std::shared_ptr<CornerBlendCurve> blend = std::make_shared<CornerBlendCurve>(corner, t1, t2, d);
  [[nodiscard]] RunResult run_checked() const {
    const std::vector<Move> moves{line({0, 0, 0}, corner - d * t1, F), program::move_along(blend, F, false, 1),
                                  line(corner + d * t2, corner + 100.0 * t2, F)};
    RunResult r = run(m, moves);
    const Usage u = usage(r, m);
    EXPECT_LE(u.v, 1.0 + 1e-6);
    EXPECT_LE(u.a, 1.0 + 1e-6);
    EXPECT_LE(u.j, 1.0 + 1e-6);
    return r;
  }
};

// A corner blend turns from zero curvature at its ends to its peak inside (docs/planner.md,
// "Corner blending"): split_move cuts it (tolerances::plan_blend_parts) so that its ends, which
// allow far more than its apex, get caps of their own, and the planner brakes inside the blend
// instead of before it (naive_cam_corner1: 3.287 -> 3.200 s on the jerk = A / T machine).
TEST(MotionPlanner, ACornerBlendIsCutSoThatTheChainBrakesInsideIt) {
  const CornerBlendRun c;
  const Machine& m = c.m;
  const double F = c.F, d = c.d;
  const Vec3 corner = c.corner, t1 = c.t1;
  const CornerBlendCurve& blend = *c.blend;
  const ArcLengthTable table(blend);
  const std::vector<MovePiece> pieces = split_move(blend, table, F, m);
  ASSERT_GE(pieces.size(), 3u);
  double lowest = std::numeric_limits<double>::infinity();
  std::vector<double> caps;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (i > 0) {
      EXPECT_EQ(pieces[i].u0, pieces[i - 1].u1);
    }
    caps.push_back(speed_cap(pieces[i].geometry, F, m, tolerances::plan_centripetal_shares[0]));
    lowest = std::min(lowest, caps.back());
  }
  EXPECT_EQ(pieces.front().u0, 0.0);
  EXPECT_EQ(pieces.back().u1, 1.0);
  EXPECT_GT(caps.front(), tolerances::plan_blend_cap_ratio * lowest);
  EXPECT_GT(caps.back(), tolerances::plan_blend_cap_ratio * lowest);

  // Through the planner (line, blend, line): within the limits, and at the blend's start faster
  // than the whole blend could run at the largest centripetal share.
  const RunResult r = c.run_checked();
  const double whole_cap =
      speed_cap(path_geometry(blend, 0.0, 1.0), F, m, std::end(tolerances::plan_centripetal_shares)[-1]);
  double best = 1e9, v_there = 0.0;
  for (const auto& p : r.points)
    if ((p.position - (corner - d * t1)).norm() < best) {
      best = (p.position - (corner - d * t1)).norm();
      v_there = p.v_mm_s;
    }
  EXPECT_GT(v_there, 1.005 * whole_cap);  // (uncut, the blend runs at most at whole_cap)
}

// A span whose curvature peaks gently inside (a parabola y = c x^2 / L over |x| <= L as one cubic
// span, c = 0.6: its outer quarters' caps about 1.26 times the whole's) is cut into quarters
// (tolerances::plan_span_cut_cap_ratio), so that only the part around the peak runs at the peak's
// cap. At a cut ratio of 1.5 it stayed one piece at the peak's cap.
TEST(MotionPlanner, ASpanWhoseCurvaturePeaksGentlyInsideIsCutAroundThePeak) {
  Machine m = default_machine();
  testing::set_every_axis(m, 500.0, 1000.0, 1000.0 / m.servo_period_s);
  const double L = 10.0, c = 0.6, F = 400.0;  // [mm], [-], [mm/s]
  NurbsData d;
  d.degree = 3;
  d.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  // x = L (-1 + 2t), y = L c (1 - 4t + 4t^2): Bezier points of those monomials
  const std::array<double, 4> ax{-L, 2.0 * L, 0.0, 0.0}, ay{L * c, -4.0 * L * c, 4.0 * L * c, 0.0};
  const auto bezier = [](const std::array<double, 4>& a) {
    return std::array<double, 4>{a[0], a[0] + a[1] / 3.0, a[0] + 2.0 * a[1] / 3.0 + a[2] / 3.0, a[0] + a[1] + a[2] + a[3]};
  };
  const auto bx = bezier(ax), by = bezier(ay);
  for (std::size_t i = 0; i < 4; ++i) d.points.emplace_back(bx[i], by[i], 0.0);
  const SpanPolynomialCurve span{NurbsCurve(d)};
  const ArcLengthTable table(span);
  const std::vector<MovePiece> pieces = split_move(span, table, F, m);
  ASSERT_GE(pieces.size(), 3u);
  const double share = tolerances::plan_centripetal_shares[0];
  const double whole = speed_cap(path_geometry(span, span.u_min(), span.u_max()), F, m, share);
  EXPECT_GT(speed_cap(pieces.front().geometry, F, m, share), 1.2 * whole);
  EXPECT_GT(speed_cap(pieces.back().geometry, F, m, share), 1.2 * whole);
  for (std::size_t i = 1; i < pieces.size(); ++i) EXPECT_EQ(pieces[i].u0, pieces[i - 1].u1);
}

// The slowest parts of a chain (its lows: a cut blend's two middle parts, of the same cap) are
// passed at their caps, where the path need not speed up or brake: they take the largest
// centripetal share, not the chain's (plan_chain_centripetal_share_max), up to the caps of the
// parts beside them (MotionPlanner::raise_chain_lows).
TEST(MotionPlanner, TheLowsOfAChainTakeTheLargestCentripetalShare) {
  const CornerBlendRun c;
  const Machine& m = c.m;
  const double F = c.F;
  const ArcLengthTable table(*c.blend);
  double chain_low = std::numeric_limits<double>::infinity(), largest_low = chain_low;  // [mm/s]
  for (const MovePiece& p : split_move(*c.blend, table, F, m)) {
    chain_low = std::min(chain_low, speed_cap(p.geometry, F, m, tolerances::plan_chain_centripetal_share_max));
    largest_low = std::min(largest_low, speed_cap(p.geometry, F, m, std::end(tolerances::plan_centripetal_shares)[-1]));
  }
  ASSERT_GT(largest_low, 1.03 * chain_low);
  const RunResult r = c.run_checked();
  // the slowest setpoint on the blend (where both coordinates have left the lines)
  double slowest = std::numeric_limits<double>::infinity();  // [mm/s]
  for (const auto& p : r.points)
    if (p.position.x() > c.corner.x() - c.d && p.position.y() < c.d) slowest = std::min(slowest, p.v_mm_s);
  EXPECT_GT(slowest, 1.02 * chain_low);
  EXPECT_LE(slowest, largest_low * (1.0 + 1e-9));
}

// The blend of a line into an arc (a TransitionCurve) is cut like a corner blend, so that the chain
// brakes inside it; but not where its parts would take under plan_blend_part_min_periods servo
// periods each at its cap (a spiral of tiny arcs, spiral_tight_circular, ran 2 % slower cut).
TEST(MotionPlanner, ALineToArcBlendIsCutUnlessItsPartsAreTooShortToBrakeIn) {
  Machine m = default_machine();
  testing::set_every_axis(m, 500.0, 1000.0, 1000.0 / m.servo_period_s);
  const double F = 400.0;  // [mm/s] above every cap on the blend
  const auto transition = [](double scale) {  // [mm]: a line's end into an arc of radius 15 scale
    const double turn = 20.0 * std::numbers::pi / 180.0;
    const Vec3 t(std::cos(turn), std::sin(turn), 0.0), n(-std::sin(turn), std::cos(turn), 0.0);
    return std::make_shared<TransitionCurve>(CurveEnd{Vec3::Zero(), Vec3::UnitX(), Vec3::Zero()},
                                             CurveEnd{scale * Vec3(10.0, 1.5, 0.0), t, n / (15.0 * scale)});
  };
  const auto caps_of = [&](const Curve& c) {
    const ArcLengthTable table(c);
    std::vector<double> caps;
    for (const MovePiece& p : split_move(c, table, F, m))
      caps.push_back(speed_cap(p.geometry, F, m, tolerances::plan_centripetal_shares[0]));
    return caps;
  };
  const auto large = transition(1.0);
  const std::vector<double> caps = caps_of(*large);
  ASSERT_GE(caps.size(), 3u);
  EXPECT_GT(caps.front(), tolerances::plan_blend_cap_ratio * *std::min_element(caps.begin(), caps.end()));
  // the same shape 1000 times smaller: its caps' ratios are the same, its parts 0.01 of a period
  const auto tiny = transition(1e-3);
  const double tiny_cap = speed_cap(path_geometry(*tiny, 0.0, 1.0), F, m, tolerances::plan_centripetal_shares[0]);
  EXPECT_LT(length(*tiny) / tolerances::plan_blend_parts,
            tolerances::plan_blend_part_min_periods * m.servo_period_s * tiny_cap);
  double best_part = 0.0;  // (a part's cap would pay for the cut as on the large one)
  for (int i = 0; i < tolerances::plan_blend_parts; ++i)
    best_part = std::max(best_part, speed_cap(path_geometry(*tiny, i / double(tolerances::plan_blend_parts),
                                                            (i + 1) / double(tolerances::plan_blend_parts)),
                                              F, m,
                                              tolerances::plan_centripetal_shares[0]));
  EXPECT_GT(best_part, tolerances::plan_blend_cap_ratio * tiny_cap);
  EXPECT_EQ(caps_of(*tiny).size(), 1u);
  // Through the planner (line, blend, arc): within the limits.
  const CurveEnd arc_start{large->point(1.0), large->derivatives(1.0, 1)[1].normalized(), Vec3::Zero()};
  CircleFrame f;
  const double turn = 20.0 * std::numbers::pi / 180.0;
  f.e2 = Vec3(std::cos(turn), std::sin(turn), 0.0);
  f.e1 = Vec3(std::sin(turn), -std::cos(turn), 0.0);  // from the centre to the arc's start
  f.centre = arc_start.point - 15.0 * f.e1;
  const auto arc = std::make_shared<HelixArc>(f, 15.0, std::numbers::pi / 2);
  ASSERT_LT((arc->point(0.0) - arc_start.point).norm(), 1e-9);
  const RunResult r = run(m, {line({-50, 0, 0}, {0, 0, 0}, F), program::move_along(large, F, false, 1),
                              program::move_along(arc, F, false, 2)});
  const Usage u = usage(r, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
}

TEST(MotionPlanner, TangentLineArcLineKeepsItsSpeed) {
  Machine m = default_machine();
  const double R = 20.0;
  CircleFrame f;
  f.centre = {50, R, 0};
  f.e1 = {0, -1, 0};
  f.e2 = {1, 0, 0};  // n = e1 x e2 = (0, 0, 1)
  const auto arc = std::make_shared<HelixArc>(f, R, std::numbers::pi / 2);
  const Vec3 arc_end = arc->point(1.0);
  const RunResult r = run(m, {line({0, 0, 0}, {50, 0, 0}, 100.0), program::move_along(arc, 100.0, false, 2),
                              line(arc_end, arc_end + Vec3(0, 50, 0), 100.0)});
  // Through both tangent junctions the speed stays up (no stop).
  double v_min_mid = 1e9;
  for (const auto& p : r.points)
    if (p.t_s > 0.3 && p.t_s < r.points.back().t_s - 0.3) v_min_mid = std::min(v_min_mid, p.v_mm_s);
  // Except where the curvature jumps: v^2 / R <= share J T, the share of a smooth junction:
  // sqrt(0.5 * 50000 * 0.001 * 20) = 22.4 mm/s.
  EXPECT_GT(v_min_mid, 0.99 * std::sqrt(tolerances::plan_smooth_junction_jerk_share * 50000.0 * 1e-3 * R));
  const Usage u = usage(r, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
  // On the arc every setpoint is on the circle.
  for (const auto& p : r.points)
    if (p.source_line == 2) {
      EXPECT_NEAR((p.position - f.centre).norm(), R, 1e-9);
    }
}

// Regression: when the sampler passed the end of one move and had to wait for the look-ahead at
// the next one (shorter than a period), it forgot the time of the move it had left and skipped
// 2-56 mm of path on the following one (51MeanderAve.ngc on XYZ_uneven.ini).
TEST(MotionPlanner, StreamingGivesTheSameSetpointsAsPlanningAtOnce) {
  const Machine m = default_machine();
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> angle(-0.002, 0.002), length(0.5, 8.0), tiny(0.01, 0.1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Move> moves;
    Vec3 p = Vec3::Zero();
    double heading = 0.0;
    for (int i = 0; i < 60; ++i) {
      heading += angle(rng);
      const double len = i % 3 == 1 ? tiny(rng) : length(rng);  // a short move between longer ones
      const Vec3 q = p + len * Vec3(std::cos(heading), std::sin(heading), 0.0);
      moves.push_back(line(p, q, 150.0, i + 1));
      p = q;
    }
    // All moves first, then the setpoints.
    testing::PlannerRun at_once(m);
    for (const auto& mv : moves) at_once.planner.push(mv);
    at_once.planner.finish();
    std::vector<Setpoint> expected;
    at_once.drain(expected);
    // Streaming: setpoints drained after every move.
    const RunResult streamed = run(m, moves);
    ASSERT_EQ(streamed.points.size(), expected.size()) << "trial " << trial;
    for (std::size_t k = 0; k < expected.size(); ++k) {
      // (the same times up to rounding: t - d + T against t + T - d)
      ASSERT_LE((streamed.points[k].position - expected[k].position).norm(), 1e-9)
          << "trial " << trial << " setpoint " << k;
      ASSERT_EQ(streamed.points[k].source_line, expected[k].source_line);
    }
    // And consecutive setpoints never jump: at most the largest feed times a period.
    for (std::size_t k = 1; k < expected.size(); ++k)
      ASSERT_LE((expected[k].position - expected[k - 1].position).norm(), 150.0 * m.servo_period_s * (1 + 1e-9));
  }
}

// A dwell (G4) stops the motion at the end of the moves before it and holds the position for its
// time, with setpoints carrying the dwell's line; the move after it starts from rest.
TEST(MotionPlanner, DwellHoldsThePositionForItsTime) {
  const Machine m = default_machine();
  testing::PlannerRun run_with_dwell(m);
  std::vector<Setpoint> pts;
  run_with_dwell.planner.push(line({0, 0, 0}, {10, 0, 0}, 100.0, 1));
  run_with_dwell.planner.dwell(0.25, 2);
  run_with_dwell.planner.push(line({10, 0, 0}, {10, 10, 0}, 100.0, 3));
  run_with_dwell.planner.finish();
  run_with_dwell.drain(pts);
  ASSERT_TRUE(run_with_dwell.sampler.done());
  std::size_t held = 0;
  for (const auto& p : pts)
    if (p.source_line == 2) {
      ++held;
      EXPECT_EQ(Vec3(p.position), Vec3(10, 0, 0));
      EXPECT_EQ(p.v_mm_s, 0.0);
    }
  // 0.25 s at 1 ms: 250 setpoints (one more or less where the stop falls between periods).
  EXPECT_NEAR(static_cast<double>(held), 250.0, 1.0);
  const RunResult no_dwell = run(m, {line({0, 0, 0}, {10, 0, 0}, 100.0, 1), line({10, 0, 0}, {10, 10, 0}, 100.0, 3)});
  // The corner is a near stop either way (with the dwell the moves keep the corner's jerk share:
  // a few ms faster), so the dwell adds its time.
  EXPECT_NEAR(pts.back().t_s - no_dwell.points.back().t_s, 0.25, 0.01);
  RunResult r;
  r.points = pts;
  const Usage u = usage(r, m);
  EXPECT_LE(u.j, 1.0 + 1e-6);
}

// Issue 12: pieces joined smoothly (here collinear lines) are one chain with one S-curve, so the
// speed rises across their junctions instead of every short line starting and ending at zero
// acceleration. 200 collinear lines of 0.05 mm take the time of one 10 mm line, within the limits.
// A circle of four quarter arcs: chains of smooth pieces. At the feed the centripetal part takes
// three quarters of the acceleration, so an S-curve at the cap's limits speeds up at about 0.66 A;
// the chain's speed bands let it speed up and brake at nearly A while it is slow, as one arc alone
// does (before they were given to chains of several pieces, at most 0.66 A).
TEST(MotionPlanner, AChainOfArcsSpeedsUpHarderWhereItIsSlow) {
  Machine m = default_machine();
  for (AxisLimits& axis : m.axes) axis.max_jerk = 1e6;  // [mm/s^3] the cross term 3 K v a does not bind
  const double R = 15.0, A = m.axes[0].max_acceleration;
  const double F = std::sqrt(0.75 * A * R);  // [mm/s] centripetal 0.75 A at the feed
  CircleFrame f;
  f.centre = {0, 0, 0};
  f.e1 = {1, 0, 0};
  f.e2 = {0, 1, 0};
  std::vector<Move> moves;
  for (int k = 0; k < 4; ++k) {
    moves.push_back(program::move_along(std::make_shared<HelixArc>(f, R, std::numbers::pi / 2), F, false, k + 1));
    const Vec3 e1 = f.e1;
    f.e1 = f.e2;
    f.e2 = -e1;
  }
  const RunResult r = run(m, moves);
  const Usage u = usage(r, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
  double v_max = 0.0;
  for (const auto& p : r.points) v_max = std::max(v_max, p.v_mm_s);
  EXPECT_LE(v_max, F * (1.0 + 1e-12));
  // The path acceleration while slower than 0.6 of the top speed (speeding up and braking).
  double a_slow = 0.0;
  for (std::size_t k = 1; k < r.points.size(); ++k)
    if (r.points[k].v_mm_s < 0.6 * v_max && r.points[k - 1].v_mm_s < 0.6 * v_max)
      a_slow = std::max(a_slow, std::abs(r.points[k].v_mm_s - r.points[k - 1].v_mm_s) / m.servo_period_s);
  EXPECT_GT(a_slow, 0.85 * A);
  for (const auto& p : r.points) EXPECT_NEAR(p.position.norm(), R, 1e-9);
}

TEST(MotionPlanner, CollinearShortLinesRunAsFastAsOneLine) {
  const Machine m = default_machine();
  std::vector<Move> short_lines;
  for (int i = 0; i < 200; ++i) short_lines.push_back(line({0.05 * i, 0, 0}, {0.05 * (i + 1), 0, 0}, 150.0, i + 1));
  const RunResult chained = run(m, short_lines);
  const RunResult single = run(m, {line({0, 0, 0}, {10, 0, 0}, 150.0, 1)});
  EXPECT_NEAR(chained.points.back().t_s, single.points.back().t_s, 0.01 * single.points.back().t_s);
  EXPECT_EQ(Vec3(chained.points.back().position), Vec3(10, 0, 0));
  const Usage u = usage(chained, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
  // Every line gets setpoints in order, and none is skipped by more than a period's travel.
  for (std::size_t k = 1; k < chained.points.size(); ++k) {
    ASSERT_GE(chained.points[k].source_line, chained.points[k - 1].source_line);
    ASSERT_LE((chained.points[k].position - chained.points[k - 1].position).norm(),
              150.0 * m.servo_period_s * (1 + 1e-9));
  }
}

}  // namespace
}  // namespace kontur::plan

namespace kontur::plan {
namespace {

// Issue 20, case 6 (163 of its failures): `F427 / G1 X-1 / G1 X0` on a machine whose acceleration
// can change within one period (v 75 mm/s, a 735 mm/s^2, jerk 1e8 mm/s^3): the reversal passed
// with a velocity step worth a tenth of the acceleration on top of the full braking, 1.078 times
// the limit. On such a machine a corner is a stop; on an ordinary one (J T << A) it is not.
TEST(MotionPlanner, ReversalOnAMachineWhoseAccelerationChangesWithinAPeriodKeepsTheAcceleration) {
  Machine stiff = default_machine();
  testing::set_every_axis(stiff, 75.0, 735.0, 1e8);
  const double feed = 427.0 / 60.0;
  for (const Machine& m : {stiff, default_machine()}) {
    testing::PlannerRun p(m);
    std::vector<trajectory::Setpoint> points;
    p.planner.push(program::move_along(std::make_shared<LineSegment>(Vec3(0, 0, 0), Vec3(-1, 0, 0)), feed, false, 3));
    p.planner.push(program::move_along(std::make_shared<LineSegment>(Vec3(-1, 0, 0), Vec3(0, 0, 0)), feed, false, 4));
    p.planner.finish();
    p.drain(points);
    double a_max = 0.0;
    for (std::size_t k = 2; k < points.size(); ++k)
      a_max = std::max(a_max, std::abs(points[k].position[0] - 2 * points[k - 1].position[0] + points[k - 2].position[0]) /
                                  (m.servo_period_s * m.servo_period_s));
    EXPECT_LE(a_max, m.axes[0].max_acceleration * (1 + 1e-6)) << "jerk " << m.axes[0].max_jerk;
    EXPECT_EQ(points.back().position[0], 0.0);
  }
}

}  // namespace
}  // namespace kontur::plan

namespace kontur::plan {
namespace {

// Issue 12: chains closed where the caps change (here collinear lines whose feeds rise by 1.75
// times each) are released through one profile where that is faster: the speed goes on rising
// through their junctions instead of every chain starting and ending at zero acceleration.
TEST(MotionPlanner, AccelerationIsCarriedAcrossTheJunctionsOfChainsOfRisingFeeds) {
  const Machine m = default_machine();
  const double A = m.axes[0].max_acceleration;
  std::vector<Move> moves;
  double x = 0.0, feed = 12.0;
  const std::array<double, 6> lengths{0.3, 0.15, 0.25, 0.4, 0.7, 1.2};  // [mm]
  for (int i = 0; i < 6; ++i, feed *= 1.75) {
    const double len = lengths[static_cast<std::size_t>(i)];
    moves.push_back(line({x, 0, 0}, {x + len, 0, 0}, feed, i + 1));
    x += len;
  }
  const RunResult r = run(m, moves);
  const Usage u = usage(r, m);
  EXPECT_LE(u.v, 1.0 + 1e-6);
  EXPECT_LE(u.a, 1.0 + 1e-6);
  EXPECT_LE(u.j, 1.0 + 1e-6);
  EXPECT_EQ(Vec3(r.points.back().position), Vec3(x, 0, 0));
  // Where lines 3, 4 and 5 begin (their first setpoint) the speed is still rising hard (each
  // chain alone starts and ends at zero acceleration: 0.176 s in place of 0.151 s).
  int carried = 0;
  for (std::size_t k = 1; k < r.points.size(); ++k)
    if (r.points[k].source_line != r.points[k - 1].source_line && r.points[k].source_line >= 3 &&
        r.points[k].source_line <= 5) {
      EXPECT_GT((r.points[k].v_mm_s - r.points[k - 1].v_mm_s) / m.servo_period_s, 0.25 * A)
          << "line " << r.points[k].source_line;
      ++carried;
    }
  EXPECT_EQ(carried, 3);
  EXPECT_LT(r.points.back().t_s, 0.16);
}

}  // namespace
}  // namespace kontur::plan
