// Valid but unkind programs (issue 20): degenerate splines, cusps, near-closed arcs, rounded
// conics and repeated points run to the end within every limit, in bounded time, and the
// independent check raises no false alarm on setpoints that lie on the path. Each program runs on
// the default machine (1 ms) and on the same machine at 125 us, where a jump shows 512 times
// larger as jerk.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/pipeline.hpp>
#include <string>

namespace kontur {
namespace {

constexpr const char* kHead = "G21 G90 G17 G94 F600\n";

struct Outcome {
  RunResult run;
  std::string program;
};

// Runs `body` (after kHead) on the default machine with the servo period `period_s` [s].
Outcome run_program(const std::string& name, const std::string& body, double period_s) {
  Machine m = default_machine();
  m.servo_period_s = period_s;
  const auto path = std::filesystem::temp_directory_path() / ("kontur_unkind_" + name + ".ngc");
  const std::string text = std::string(kHead) + body + "M2\n";
  std::ofstream(path) << text;
  Pipeline pipeline(m);
  Outcome o{pipeline.run(path.string()), text};
  std::filesystem::remove(path);
  return o;
}

// Passes on both periods, and takes at most `max_time_s` [s] (no crawl at a speed of 1e-27 mm/s).
void expect_runs_within_limits(const std::string& name, const std::string& body, double max_time_s) {
  for (const double period_s : {1e-3, 125e-6}) {
    const Outcome o = run_program(name, body, period_s);
    SCOPED_TRACE(o.program + " at T = " + std::to_string(period_s) + " s");
    EXPECT_TRUE(o.run.passed) << o.run.summary_json.substr(0, 2000);
    EXPECT_LE(o.run.total_time_s, max_time_s);
    EXPECT_LE(o.run.check.end_error_mm, 1e-9);
  }
}

TEST(UnkindInput, NurbsWithATinyFirstSpanDoesNotHang) {  // case 1
  expect_runs_within_limits("case1", "G6.2 P2 K0 X0 Y0 Z0\nK0 X0.001 Y0 Z0 R2\nK0.5 X0.001 Y0 Z0 R3\nK1\nK1\n", 1.0);
}

TEST(UnkindInput, NurbsWhoseKnotsEndAtThreeAndWhoseEndPointIsRepeatedDoesNotHang) {  // case 2
  expect_runs_within_limits("case2", "G6.2 P4 K0 X0 Y0 Z0\nK0 X1 Y0 Z0\nK0 X1 Y1 Z0\nK0 X2 Y1 Z0\nK1 X2 Y1 Z0\nK3\nK3\nK3\nK3\n",
                            2.0);
}

TEST(UnkindInput, NearlyClosedQuadraticBezierDoesNotHang) {  // case 3, first program
  expect_runs_within_limits("case3a", "G5.1 X0 Y0.0001 I1 J1\n", 2.0);
}

TEST(UnkindInput, CubicBezierWithTenthMicrometreHandlesRunsAsTheLineItIs) {  // case 3, second program
  expect_runs_within_limits("case3b", "G5 X1 Y1 I0.0000001 J0 P0 Q-0.0000001\n", 1.0);
}

TEST(UnkindInput, NurbsWithARepeatedControlPointAtSmallScaleDoesNotHang) {  // case 4
  expect_runs_within_limits("case4", "G5.2 L3\nX0.015 Y0.04\nX0.015 Y0.04\nX0.03 Y0.05\nX0.04 Y0.02\nG5.3\n", 1.0);
}

TEST(UnkindInput, CuspOfABezierThatTurnsBackAlongItselfIsAStop) {  // case 7
  expect_runs_within_limits("case7", "G5.1 X0.5 Y0.5 I1 J1\n", 1.0);
}

TEST(UnkindInput, ConicWithPointsRoundedOffItsPlaneEndsAtItsProgrammedEnd) {  // case 8
  // an ellipse (10 x 5 mm) in a plane tilted by 30 degrees, its points rounded to 4 decimals
  expect_runs_within_limits("case8",
                            "G1 X10 Y0 Z0\nCONIC X-9.3969 Y1.4810 Z0.8551 I1=7.6604 J1=2.7834 K1=1.6070 I2=1.7365 "
                            "J2=4.2643 K2=2.4620 I3=-5.0000 J3=3.7500 K3=2.1651\nG1 X-12 Y0 Z0\n",
                            60.0);
}

TEST(UnkindInput, ArcEndingJustShortOfItsStartIsAFullCircleAndTheNextMoveStartsThere) {  // case 9
  expect_runs_within_limits("case9", "G3 X0 Y-0.00005 I-1 J0\nG1 X1 Y1\n", 5.0);
}

TEST(UnkindInput, DegreeOneNurbsWithARepeatedPointGetsNoFalseAlarm) {  // case 11
  expect_runs_within_limits("case11", "G5.2 L2\nX1 Y0\nX1 Y0\nX1 Y1\nX0 Y1\nG5.3\n", 5.0);
}

TEST(UnkindInput, NurbsWithWeightsFromOneHundredthToOneHundredRunsAtItsTrueCurvature) {  // "absurd, not failing"
  // took 2,245 s at 0.001 mm/s: one speed cap for the whole span, set by its sharpest point
  expect_runs_within_limits("weights", "G6.2 P4 K0 X0 Y0 Z0 R100\nK0 X0 Y-1 Z0 R0.01\nK0 X1 Y1 Z0 R1\nK0 X1 Y2 Z0 R1\nK1\nK1\nK1\nK1\n",
                            2.0);
}

TEST(StationaryPoints, FindsACuspInsideASpanAndARepeatedEndPoint) {
  // quadratic Bezier (0,0) (1,1) (0.5,0.5): C'(u) = (2 - 3u)(1, 1), zero at u = 2/3
  NurbsData cusp;
  cusp.degree = 2;
  cusp.knots = {0, 0, 0, 1, 1, 1};
  cusp.points = {{0, 0, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
  const auto at = stationary_points(NurbsCurve(cusp), 1e-6, 64);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_NEAR(at[0], 2.0 / 3.0, 1e-12);
  // cubic with its last control point repeated: C' = 0 at the end only
  NurbsData end;
  end.degree = 3;
  end.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  end.points = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {2, 1, 0}};
  const auto e = stationary_points(NurbsCurve(end), 1e-6, 64);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0], 1.0);
  // a regular curve has none
  end.points[3] = {3, 1, 0};
  EXPECT_TRUE(stationary_points(NurbsCurve(end), 1e-6, 64).empty());
}

TEST(ConicArc, PinnedEndsAreTheProgrammedPointsAndTheTangentsStay) {
  const std::array<Vec3, 5> pts{Vec3(10, 0, 0), Vec3(7.6604, 2.7834, 1.6070), Vec3(1.7365, 4.2643, 2.4620),
                                Vec3(-5.0, 3.75, 2.1651), Vec3(-9.3969, 1.4810, 0.8551)};
  ConicOptions options;
  options.plane_tolerance_mm = 1e-3;
  const ConicThroughPoints k = conic_through_points(pts, options);
  const ConicArc arc = k.curve();
  EXPECT_EQ(arc.point(arc.u_min()), pts[0]);
  EXPECT_EQ(arc.point(arc.u_max()), pts[4]);
  EXPECT_GT(arc.end_offset_mm().norm(), 1e-6);  // the rounding put r5 off the conic's plane
  // the smooth step leaves the derivatives at both ends as the conic's own
  ConicArc raw(arc.focus_mm(), arc.x_axis(), arc.y_axis(), arc.focal_parameter_mm(), arc.eccentricity(),
               arc.phi_start_rad(), arc.sweep_rad());
  for (const double u : {arc.u_min(), arc.u_max()}) {
    const Derivatives a = arc.derivatives(u, 2), b = raw.derivatives(u, 2);
    EXPECT_LE((a[1] - b[1]).norm(), 1e-12 * b[1].norm());
    EXPECT_LE((a[2] - b[2]).norm(), 1e-12 * b[2].norm());
  }
}

}  // namespace
}  // namespace kontur
