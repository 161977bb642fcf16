// Smoothing of dense G01 within the G64 tolerance (program/line_smoother.hpp) and the fit under it
// (geometry/polyline_fit.hpp): the fitted curve, evaluated by OpenCASCADE, stays within the
// tolerance of the programmed lines and passes within it of every vertex; it is tangent to the
// lines around it with zero curvature at its ends and curvature-continuous at every vertex; the
// stage keeps corners, exact stops and short runs; the checker measures setpoints against the
// programmed lines and fails a path that leaves them.
#include <gtest/gtest.h>

#include <Extrema_ExtPC.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <kontur/geometry/curve_piece.hpp>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/polyline_fit.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/program/line_smoother.hpp>
#include <kontur/tolerances.hpp>
#include <kontur/program/program_path.hpp>
#include <kontur/verify/checker.hpp>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "support/occt_oracle.hpp"
#include "support/planner_run.hpp"

namespace kontur {
namespace {

constexpr double pi = 3.14159265358979323846;

// Points every `step_mm` along a circle of radius `r_mm` over `angle` [rad], rounded to `grid_mm`
// (as a CAM post rounds its coordinates).
std::vector<Vec3> rounded_arc(double r_mm, double angle, double step_mm, double grid_mm) {
  std::vector<Vec3> p;
  const int n = static_cast<int>(std::ceil(r_mm * angle / step_mm));
  for (int i = 0; i <= n; ++i) {
    const double a = angle * i / n;
    Vec3 q(r_mm * std::sin(a), r_mm * std::cos(a), 0.0);
    for (int k = 0; k < 3; ++k) q[k] = std::round(q[k] / grid_mm) * grid_mm;
    if (p.empty() || (q - p.back()).norm() > 0.0) p.push_back(q);
  }
  return p;
}

// Distance [mm] from p to the whole polyline (every line: independent of the fit's local search).
double distance_to_polyline(const std::vector<Vec3>& v, const Vec3& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < v.size(); ++i) d = std::min(d, segment_distance(p, v[i], v[i + 1]));
  return d;
}

// Distance [mm] from p to the curve by OpenCASCADE (its extrema and both ends).
double occt_distance(const Handle(Geom_BSplineCurve) & c, const Vec3& p) {
  GeomAdaptor_Curve adaptor(c);
  const gp_Pnt q(p.x(), p.y(), p.z());
  double d2 = std::min(q.SquareDistance(c->Value(c->FirstParameter())), q.SquareDistance(c->Value(c->LastParameter())));
  Extrema_ExtPC ext(q, adaptor);
  if (ext.IsDone())
    for (int i = 1; i <= ext.NbExt(); ++i) d2 = std::min(d2, ext.SquareDistance(i));
  return std::sqrt(d2);
}

struct FitMeasure {
  double curve_to_lines_mm = 0.0;   // largest distance of the curve (OCCT samples) from the polyline
  double vertex_to_curve_mm = 0.0;  // largest distance of a vertex from the curve (OCCT extrema)
  double max_curvature = 0.0;       // [1/mm]
};

FitMeasure measure(const PolylineFit& fit, const std::vector<Vec3>& v) {
  FitMeasure m;
  const Handle(Geom_BSplineCurve) c = testing::to_occt(fit.curve.data());
  for (std::size_t j = 0; j + 1 < fit.vertex_u.size(); ++j)
    for (int q = 0; q <= 40; ++q) {
      const double u = fit.vertex_u[j] + (fit.vertex_u[j + 1] - fit.vertex_u[j]) * q / 40.0;
      gp_Pnt p;
      gp_Vec d1, d2;
      c->D2(u, p, d1, d2);
      m.curve_to_lines_mm = std::max(m.curve_to_lines_mm, distance_to_polyline(v, Vec3(p.X(), p.Y(), p.Z())));
      m.max_curvature = std::max(m.max_curvature, d1.Crossed(d2).Magnitude() / std::pow(d1.Magnitude(), 3));
    }
  for (const Vec3& p : v) m.vertex_to_curve_mm = std::max(m.vertex_to_curve_mm, occt_distance(c, p));
  return m;
}

TEST(PolylineFit, RoundedCircleWithinToleranceByOpenCascade) {
  // circle_small_segments_ncd's kind of input: 15 um lines on a 25.4 mm circle, coordinates
  // rounded to 2.54 um (each line turns by up to 0.2 rad where the true circle turns 0.0006).
  const double tol = 0.01;
  const std::vector<Vec3> v = rounded_arc(25.4, pi / 6, 0.015, 0.00254);
  const Vec3 t0 = (v[1] - v[0]).normalized(), t1 = (v[v.size() - 1] - v[v.size() - 2]).normalized();
  const auto fit = fit_polyline(v, t0, t1, tol);
  ASSERT_TRUE(fit.has_value());
  const FitMeasure m = measure(*fit, v);
  EXPECT_LE(m.curve_to_lines_mm, tol);
  EXPECT_LE(m.vertex_to_curve_mm, tol);
  // Smooth: the polyline's own turns would ask for a curvature of 10 / mm, the circle has 0.039.
  EXPECT_LT(m.max_curvature, 0.2);
  // The ends: exact, tangent to the given directions, no curvature (the lines around it join smoothly).
  const Curve& c = fit->curve;
  for (const auto& [u, p, t] : {std::tuple{c.u_min(), v.front(), t0}, std::tuple{c.u_max(), v.back(), t1}}) {
    const Derivatives d = c.derivatives(u, 2);
    EXPECT_LE((d[0] - p).norm(), 1e-12);
    EXPECT_LE((d[1].normalized() - t).norm(), 1e-12);
    EXPECT_LE(d[1].cross(d[2]).norm() / std::pow(d[1].norm(), 3), 1e-9);
  }
}

TEST(PolylineFit, CurvatureContinuousAtEveryVertex) {
  const std::vector<Vec3> v = rounded_arc(10.0, pi / 3, 0.05, 0.001);
  const auto fit = fit_polyline(v, (v[1] - v[0]).normalized(), (v.back() - v[v.size() - 2]).normalized(), 0.01);
  ASSERT_TRUE(fit.has_value());
  for (std::size_t i = 1; i + 1 < fit->vertex_u.size(); ++i) {
    const Derivatives l = fit->curve.derivatives_left(fit->vertex_u[i], 2),
                      r = fit->curve.derivatives(fit->vertex_u[i], 2);
    EXPECT_LE((l[0] - r[0]).norm(), 1e-12);
    EXPECT_LE((l[1] - r[1]).norm(), 1e-9);
    EXPECT_LE((l[2] - r[2]).norm(), 1e-6 * std::max(1.0, r[2].norm()));
  }
}

TEST(PolylineFit, SeededRandomPolylinesWithinToleranceByOpenCascade) {
  // Random walks in space: lines of 0.01-0.5 mm turning by up to 25 degrees, tolerances 5-100 um.
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> len(0.01, 0.5), tol_d(0.005, 0.1), turn(0.0, 25.0 * pi / 180), uni(0.0, 1.0);
  int fitted = 0;
  const int cases = 40;
  for (int k = 0; k < cases; ++k) {
    const double tol = tol_d(rng);
    std::vector<Vec3> v{Vec3::Zero()};
    Vec3 t = Vec3::UnitX();
    const int n = 8 + static_cast<int>(uni(rng) * 150);
    for (int i = 0; i < n; ++i) {
      // turn t by a random angle about a random axis normal to it
      Vec3 axis = t.unitOrthogonal();
      const double phi = 2 * pi * uni(rng);
      axis = Eigen::AngleAxisd(phi, t) * axis;
      t = (Eigen::AngleAxisd(turn(rng), axis) * t).normalized();
      v.push_back(v.back() + len(rng) * t);
    }
    const auto fit = fit_polyline(v, (v[1] - v[0]).normalized(), (v.back() - v[v.size() - 2]).normalized(), tol);
    if (!fit) continue;
    ++fitted;
    const FitMeasure m = measure(*fit, v);
    EXPECT_LE(m.curve_to_lines_mm, tol) << "case " << k;
    EXPECT_LE(m.vertex_to_curve_mm, tol) << "case " << k;
  }
  EXPECT_GE(fitted, cases * 9 / 10);
  std::printf("fitted %d of %d random polylines\n", fitted, cases);
}

TEST(PolylineFit, RefusesWhatItCannotFit) {
  const Vec3 x = Vec3::UnitX();
  EXPECT_FALSE(fit_polyline({Vec3::Zero(), x, 2 * x, 3 * x}, x, x, 0.01).has_value());            // too few lines
  EXPECT_FALSE(fit_polyline({Vec3::Zero(), x, x, 2 * x, 3 * x, 4 * x}, x, x, 0.01).has_value());  // a line of no length
  EXPECT_FALSE(fit_polyline({Vec3::Zero(), x, 2 * x, 3 * x, 4 * x}, x, x, 0.0).has_value());      // no tolerance
}

// A G1 line move with the G64 tolerance `tol_mm` at its end.
program::Move line_move(const Vec3& a, const Vec3& b, double tol_mm, long line, bool exact_stop = false) {
  program::Move m = program::move_along(std::make_shared<const LineSegment>(a, b), 100.0, exact_stop, line);
  m.type = "line";
  m.corner_tolerance_mm = exact_stop ? 0.0 : tol_mm;
  return m;
}

std::vector<program::Move> smooth(const std::vector<Vec3>& v, double tol_mm, bool enabled = true,
                                  long exact_stop_line = -1) {
  program::LineSmoother s(enabled);
  std::vector<program::Move> out;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    const long line = static_cast<long>(i + 1);
    s.push(line_move(v[i], v[i + 1], tol_mm, line, line == exact_stop_line), out);
  }
  s.flush(out);
  return out;
}

TEST(LineSmoother, ARunBecomesPiecesOfOneCurveWithTheirLines) {
  const std::vector<Vec3> v = rounded_arc(5.0, pi / 4, 0.1, 0.001);
  const auto out = smooth(v, 0.01);
  ASSERT_EQ(out.size(), v.size() - 1);  // one move per programmed line
  EXPECT_FALSE(out.front().lines.has_value());
  EXPECT_FALSE(out.back().lines.has_value());
  EXPECT_NE(dynamic_cast<const LineSegment*>(out.front().curve.get()), nullptr);
  EXPECT_NE(dynamic_cast<const LineSegment*>(out.back().curve.get()), nullptr);
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].source_line, static_cast<long>(i + 1));
    if (i > 0) {
      const Curve &a = *out[i - 1].curve, &b = *out[i].curve;
      EXPECT_LE((a.point(a.u_max()) - b.point(b.u_min())).norm(), 1e-12) << i;
    }
    if (i == 0 || i + 1 == out.size()) continue;
    ASSERT_TRUE(out[i].lines.has_value());
    EXPECT_EQ(out[i].lines->line, i - 1);
    EXPECT_NE(dynamic_cast<const CurvePiece*>(out[i].curve.get()), nullptr);
    EXPECT_GT(out[i].length_mm, 0.0);
  }
}

// Regression guard: a run longer than the window (smooth_max_run_lines) was cut into runs ending
// and starting with a straight line, a corner of the programmed polyline between them:
// circle_small_segments (9,997 lines of a 25 mm circle) slowed to 38 mm/s every 2,000 lines. The
// runs now continue each other's curve: every line is a piece of a curve, contiguous, tangent and
// curvature continuous at every junction (cuts included: the planner sees them smooth), and within
// the tolerance of the programmed lines.
TEST(LineSmoother, ALongRunIsCutCurvatureContinuously) {
  const double tol = 0.01;
  const std::vector<Vec3> v = rounded_arc(25.4, 2.95, 0.015, 0.00254);
  ASSERT_GT(v.size(), 2 * tolerances::smooth_max_run_lines + 10);
  const auto out = smooth(v, tol);
  ASSERT_EQ(out.size(), v.size() - 1);
  const Machine machine = default_machine();
  int cuts = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].source_line, static_cast<long>(i + 1));
    if (i == 0 || i + 1 == out.size()) continue;
    ASSERT_NE(dynamic_cast<const CurvePiece*>(out[i].curve.get()), nullptr) << i;
    ASSERT_TRUE(out[i].lines.has_value()) << i;
    const Curve &a = *out[i - 1].curve, &b = *out[i].curve;
    const Derivatives da = a.derivatives_left(a.u_max(), 3), db = b.derivatives(b.u_min(), 3);
    EXPECT_LE((da[0] - db[0]).norm(), 1e-12) << i;
    if (i >= 2) {
      EXPECT_TRUE(plan::junction(da, db, machine).smooth()) << "line " << i + 1;
      const auto ca = static_cast<const CurvePiece*>(out[i - 1].curve.get());
      const auto cb = static_cast<const CurvePiece*>(out[i].curve.get());
      if (ca->whole() != cb->whole()) ++cuts;
    }
    // every piece within the tolerance of the programmed lines
    for (int q = 0; q <= 4; ++q) {
      const Vec3 p = b.point(b.u_min() + (b.u_max() - b.u_min()) * q / 4.0);
      ASSERT_LE(distance_to_polyline(v, p), tol) << i;
    }
  }
  EXPECT_EQ(cuts, static_cast<int>((v.size() - 3) / tolerances::smooth_max_run_lines));
}

// LinuxCNC's spiral_tangent_test read in inches: 2,000 lines of 0.254 mm (25 tolerances) whose turn
// grows to 23 degrees. A curve with zero curvature at its ends cannot follow the tight end, and
// the whole run stayed as programmed: 2,000 corners, 62.9 s on XYZ.ini against LinuxCNC's 17.6 s.
// Now the fit frees the curvature at the run's ends where it must, and a run whose fit still
// fails is fitted in halves: nearly every line is smoothed, within the tolerance.
TEST(LineSmoother, ATightSpiralOfLongLinesIsSmoothedWhereTheFitHolds) {
  const double tol = 0.01, step = 0.254;
  std::vector<Vec3> v{Vec3::Zero()};
  double heading = 0.0;
  for (int i = 0; i < 2000; ++i) {
    v.push_back(v.back() + step * Vec3(std::cos(heading), std::sin(heading), 0.0));
    heading -= 0.4 * i / 2000.0;  // [rad] the turn at each vertex, up to 0.4 (23 degrees)
  }
  const auto out = smooth(v, tol);
  ASSERT_EQ(out.size(), v.size() - 1);
  std::size_t smoothed = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(out[i].source_line, static_cast<long>(i + 1));
    if (!out[i].lines) continue;
    ++smoothed;
    const Curve& c = *out[i].curve;
    for (int q = 0; q <= 8; ++q)
      ASSERT_LE(distance_to_polyline(v, c.point(c.u_min() + (c.u_max() - c.u_min()) * q / 8.0)), tol) << i;
  }
  EXPECT_GT(smoothed, 1900u);
}

// Collinear lines (performance/short_segments_0.001: 3,000 lines of 0.001 in along X) are already
// smooth for the planner at every junction: fitting them gained nothing (1.147 s either way on
// XYZ.ini) and cost two fifths of the run, in the fit and in the curve pieces' geometry.
TEST(LineSmoother, ACollinearRunStaysLines) {
  std::vector<Vec3> v;
  for (int i = 0; i <= 3000; ++i) v.emplace_back(0.0254 * i, 0.0, 0.0);
  const auto out = smooth(v, 0.01);
  ASSERT_EQ(out.size(), v.size() - 1);
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_FALSE(out[i].lines.has_value()) << i;
    ASSERT_NE(dynamic_cast<const LineSegment*>(out[i].curve.get()), nullptr) << i;
    EXPECT_EQ(out[i].curve->point(out[i].curve->u_max()), v[i + 1]) << i;
  }
  // A kink of a micro-radian is a turn the planner sees: the window holding it is still fitted
  // (the first 2,000 lines; the straight rest after the cut stays lines).
  v[1500].y() = 1e-6 * 0.0254;
  const auto kinked = smooth(v, 0.01);
  std::size_t smoothed = 0;
  for (const auto& m : kinked) smoothed += m.lines.has_value() ? 1 : 0;
  EXPECT_TRUE(kinked[1499].lines.has_value());
  EXPECT_TRUE(kinked[1500].lines.has_value());
  EXPECT_EQ(smoothed, tolerances::smooth_max_run_lines);
}

TEST(LineSmoother, CornersExactStopsShortRunsAndRapidsStayAsProgrammed) {
  // A 90 degree corner in the middle of dense lines: two runs, the corner kept.
  std::vector<Vec3> v;
  for (int i = 0; i <= 10; ++i) v.emplace_back(0.1 * i, 0.002 * (i % 2), 0.0);
  for (int i = 1; i <= 10; ++i) v.emplace_back(1.0, 0.1 * i, 0.0);
  const auto out = smooth(v, 0.01);
  ASSERT_EQ(out.size(), v.size() - 1);
  EXPECT_FALSE(out[9].lines.has_value());   // the line into the corner
  EXPECT_FALSE(out[10].lines.has_value());  // the line out of it
  // G61 at line 6: the run stops there.
  const auto stopped = smooth(rounded_arc(5.0, pi / 4, 0.1, 0.001), 0.01, true, 6);
  EXPECT_FALSE(stopped[5].lines.has_value());
  EXPECT_FALSE(stopped[6].lines.has_value());
  EXPECT_TRUE(stopped[10].lines.has_value());
  // Five lines: too few.
  for (const auto& m : smooth(rounded_arc(5.0, 0.05, 0.05, 0.001), 0.01)) EXPECT_FALSE(m.lines.has_value());
  // Switched off, or no tolerance (G64 without blending: exact path): unchanged.
  for (const auto& m : smooth(rounded_arc(5.0, pi / 4, 0.1, 0.001), 0.01, false)) EXPECT_FALSE(m.lines.has_value());
  for (const auto& m : smooth(rounded_arc(5.0, pi / 4, 0.1, 0.001), 0.0)) EXPECT_FALSE(m.lines.has_value());
  // Rapids are not smoothed.
  program::LineSmoother s;
  std::vector<program::Move> rapids;
  const auto arc = rounded_arc(5.0, pi / 4, 0.1, 0.001);
  for (std::size_t i = 0; i + 1 < arc.size(); ++i) {
    program::Move m = line_move(arc[i], arc[i + 1], 0.01, static_cast<long>(i + 1));
    m.type = "rapid";
    s.push(m, rapids);
  }
  s.flush(rapids);
  for (const auto& m : rapids) EXPECT_FALSE(m.lines.has_value());
}

// Regression guard: random_lines_0.001in (LinuxCNC's test of a random walk of lines 2.5
// tolerances long, turning by 35 degrees and more at many vertices) was cut into runs at every
// turn over 30 degrees, each a near stop: 19.5 s against LinuxCNC's 12.7 s. Such turns between
// lines short against the tolerance are noise within it, not corners: they join the run, and the
// curve stays within the tolerance of the programmed lines. A sharp turn next to a line longer than
// smooth_soft_corner_line_tolerances tolerances stays a corner.
TEST(LineSmoother, SharpTurnsBetweenLinesShortAgainstTheToleranceJoinTheRun) {
  const double tol = 0.01, step = 2.5 * tol;  // [mm]
  std::mt19937 rng(20261204);
  std::uniform_real_distribution<double> turn(0.6, 0.9);  // [rad]: 34 .. 52 degrees
  std::bernoulli_distribution left(0.5);
  std::vector<Vec3> v{Vec3::Zero()};
  double heading = 0.0;  // [rad]
  for (int i = 0; i < 80; ++i) {
    heading += (left(rng) ? 1.0 : -1.0) * turn(rng);
    v.push_back(v.back() + step * Vec3(std::cos(heading), std::sin(heading), 0.0));
  }
  const auto out = smooth(v, tol);
  ASSERT_EQ(out.size(), v.size() - 1);
  // Every vertex turns by 34 degrees or more: before, no line was smoothed. Now the lines are
  // pieces of curves (a fit that cannot follow the walk is halved: its halves' end lines stay
  // lines), each within the tolerance of the programmed lines.
  int smoothed = 0;
  for (std::size_t i = 1; i + 1 < out.size(); ++i) {
    if (!out[i].lines) continue;
    ++smoothed;
    const Curve& c = *out[i].curve;
    for (int q = 0; q <= 50; ++q) {
      const double u = c.u_min() + (c.u_max() - c.u_min()) * q / 50.0;
      EXPECT_LE(distance_to_polyline(v, c.point(u)), tol) << "line " << i + 1 << " u " << u;
    }
  }
  EXPECT_GE(smoothed, 70);
  // The same walk with one line 5 tolerances long: the turns at its ends stay corners.
  std::vector<Vec3> w(v.begin(), v.begin() + 31);
  const Vec3 long_dir = (v[31] - v[30]).normalized();
  w.push_back(w.back() + 5.0 * tol * long_dir);
  for (std::size_t i = 31; i + 1 < v.size(); ++i) w.push_back(w.back() + (v[i + 1] - v[i]));
  const auto cut = smooth(w, tol);
  ASSERT_EQ(cut.size(), w.size() - 1);
  EXPECT_FALSE(cut[30].lines.has_value());  // the long line (line 31)
  EXPECT_FALSE(cut[29].lines.has_value());  // the run before ends with its last line
  EXPECT_FALSE(cut[31].lines.has_value());  // the run after starts with its first line
  EXPECT_TRUE(cut[15].lines.has_value());
  EXPECT_TRUE(cut[45].lines.has_value());
}

TEST(LineSmoother, NaiveCamToleranceWidensTheSmoothing) {
  const auto v = rounded_arc(5.0, pi / 4, 0.1, 0.001);
  program::LineSmoother s;
  std::vector<program::Move> out;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    program::Move m = line_move(v[i], v[i + 1], 0.01, static_cast<long>(i + 1));
    m.naive_cam_tolerance_mm = 0.05;  // G64 P0.01 Q0.05
    s.push(m, out);
  }
  s.flush(out);
  ASSERT_TRUE(out[1].lines.has_value());
  EXPECT_EQ(out[1].lines->tolerance_mm, 0.05);
}

TEST(LineSmoother, CheckerMeasuresSetpointsAgainstTheProgrammedLines) {
  Machine machine = default_machine();
  const double tol = 0.01;
  std::vector<program::Move> moves = smooth(rounded_arc(20.0, pi / 2, 0.05, 0.0025), tol);
  for (std::size_t i = 0; i < moves.size(); ++i) moves[i].id = static_cast<program::MoveId>(i);
  const auto setpoints = testing::plan_and_sample(machine, moves);
  auto check = [&](const std::vector<program::Move>& path) {
    verify::Checker c(path, machine);
    for (const auto& sp : setpoints) c.add(sp);
    return c.finish();
  };
  const verify::Report ok = check(moves);
  EXPECT_TRUE(ok.passed(machine));
  EXPECT_GT(ok.smoothed_lines, 0);
  EXPECT_GT(ok.max_smoothing_deviation_mm, 0.0);
  EXPECT_LE(ok.max_smoothing_deviation_mm, tol);
  // The same setpoints against programmed lines moved by twice the tolerance: the check fails.
  std::vector<program::Move> moved = moves;
  auto shifted = std::make_shared<std::vector<Vec3>>(*moves[1].lines->vertices);
  for (Vec3& p : *shifted) p += Vec3(0.0, 0.0, 2 * tol);
  for (auto& m : moved)
    if (m.lines) m.lines->vertices = shifted;
  const verify::Report bad = check(moved);
  EXPECT_FALSE(bad.passed(machine));
  EXPECT_GT(bad.max_smoothing_deviation_mm, 1.9 * tol);
  ASSERT_FALSE(bad.failures(machine).empty());
}

// The moves of `program_text` on the default machine, as `kontur run` makes them.
std::vector<program::Move> path_of(const std::string& name, const std::string& program_text) {
  const auto file = std::filesystem::temp_directory_path() / ("kontur_smoothing_" + name + ".ngc");
  std::ofstream(file) << program_text;
  const Machine machine = default_machine();
  program::ProgramPath path(machine, true, true);
  path.read(file.string(), {});
  std::filesystem::remove(file);
  return path.moves();
}

TEST(LineSmoother, G64P0IsG64WithoutPAsInLinuxCnc) {
  // LinuxCNC: "G64 and G64 P0" blend without a tolerance of their own; Kontur keeps the machine's
  // path tolerance for both (it never leaves a bounded tolerance), and P where it is given.
  std::string lines;
  for (int i = 1; i <= 40; ++i)
    lines += "G1 X" + std::to_string(10.0 * std::sin(i * 0.02)) + " Y" +
             std::to_string(10.0 * (1 - std::cos(i * 0.02))) + "\n";
  auto tolerances = [](const std::vector<program::Move>& moves) {
    std::vector<double> t;
    for (const auto& m : moves)
      if (m.lines) t.push_back(m.lines->tolerance_mm);
    return t;
  };
  const double machine_tol = default_machine().path_tolerance_mm;
  for (const char* mode : {"G64 P0", "G64"}) {
    const auto t = tolerances(path_of("p0", std::string("G21 G90 F600 ") + mode + "\n" + lines + "M2\n"));
    EXPECT_GT(t.size(), 30U) << mode;
    for (double x : t) EXPECT_EQ(x, machine_tol) << mode;
  }
  const auto given = tolerances(path_of("p005", "G21 G90 F600 G64 P0.05\n" + lines + "M2\n"));
  EXPECT_GT(given.size(), 30U);
  for (double x : given) EXPECT_EQ(x, 0.05);
  // G61: the exact path, nothing smoothed
  EXPECT_TRUE(tolerances(path_of("g61", "G21 G90 F600 G61\n" + lines + "M2\n")).empty());
}

}  // namespace
}  // namespace kontur
