// The G-code reader on small programs: geometry of every block type compared by sampled shape
// (start, end, points the curve must pass through, length), modal state, units, offsets,
// canned cycles, parameters and expressions.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/expression.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/geometry/length.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <numbers>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

constexpr double pi = std::numbers::pi;

std::vector<Block> read(const std::string& program, ReaderOptions options = {}) {
  Reader reader("test.ngc", program, options);
  std::vector<Block> blocks;
  Block b;
  while (reader.next(b)) blocks.push_back(b);
  return blocks;
}

std::string error_of(const std::string& program) {
  try {
    read(program);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-9) {
  EXPECT_NEAR((a - b).norm(), 0.0, tol) << "(" << a.transpose() << ") vs (" << b.transpose() << ")";
}

// The curve starts at block.start, ends at block.end and its length matches the block's.
void expect_consistent(const Block& b, double tol = 1e-7) {
  const Curve* c = b.curve();
  ASSERT_NE(c, nullptr);
  expect_near(c->point(c->u_min()), b.start, tol);
  expect_near(c->point(c->u_max()), b.end, tol);
  EXPECT_NEAR(*b.length_mm(), length(*c), 1e-9 * (1.0 + *b.length_mm()));
}

// Smallest distance from p to the curve, by dense sampling.
double distance_to(const Curve& c, const Vec3& p) {
  double best = 1e300;
  const int n = 20000;
  for (int i = 0; i <= n; ++i) {
    const double u = c.u_min() + (c.u_max() - c.u_min()) * i / n;
    best = std::min(best, (c.point(u) - p).norm());
  }
  return best;
}

TEST(GcodeReader, LinesRapidsFeedAndLocation) {
  const auto b = read("%\nN10 G21 G90 (comment) F600\nN20 G0 X10 Y0 Z5 ; rest\n  G1 Z-1\nX20 Y10\n%\nG1 X99\n");
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].type, BlockType::rapid);
  EXPECT_EQ(b[0].location.line, 3);
  EXPECT_EQ(b[0].location.column, 5);
  EXPECT_EQ(b[0].location.n_number, 20);
  EXPECT_EQ(*b[0].location.file, "test.ngc");
  EXPECT_EQ(b[1].type, BlockType::line);
  EXPECT_EQ(b[1].location.column, 3);
  EXPECT_DOUBLE_EQ(b[1].feed.value, 600.0);
  EXPECT_DOUBLE_EQ(*b[1].length_mm(), 6.0);
  EXPECT_NEAR(*b[2].length_mm(), std::sqrt(200.0), 1e-12);
  for (const auto& x : b) expect_consistent(x);
}

TEST(GcodeReader, InchAndIncremental) {
  const auto b = read("G20 G91 F10\nG1 X1 Y1\nX1\nG21 G90 X0 Y0\nM2\n");
  ASSERT_EQ(b.size(), 3u);
  expect_near(b[0].end, Vec3(25.4, 25.4, 0));
  expect_near(b[1].end, Vec3(50.8, 25.4, 0));
  EXPECT_DOUBLE_EQ(b[0].feed.value, 254.0);
  EXPECT_EQ(b[0].modal.units, Units::inch);
  EXPECT_EQ(b[2].modal.units, Units::mm);
  EXPECT_DOUBLE_EQ(b[2].feed.value, 254.0);  // the feed is physical: it survives G21
  expect_near(b[2].end, Vec3::Zero());
}

TEST(GcodeReader, ArcsInThreePlanesAndBothDirections) {
  // quarter circles of radius 10 from (10,0) about the origin, counter-clockwise (G3) and clockwise (G2)
  const auto b = read("F100\nG17 G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0\nG0 X10 Y0\nG2 X0 Y-10 R10\n"
                      "G18 G0 X10 Y0 Z0\nG2 Z10 X0 K0 I-10\nG19 G0 X0 Y10 Z0\nG2 Y0 Z-10 J-10 K0\n");
  ASSERT_EQ(b.size(), 8u);
  const Block& ccw = b[1];
  EXPECT_EQ(ccw.type, BlockType::arc);
  EXPECT_NEAR(*ccw.length_mm(), 5 * pi, 1e-12);
  expect_consistent(ccw);
  EXPECT_NEAR(distance_to(*ccw.curve(), Vec3(10 / std::sqrt(2.0), 10 / std::sqrt(2.0), 0)), 0.0, 1e-6);
  const Block& cw = b[3];
  EXPECT_NEAR(*cw.length_mm(), 5 * pi, 1e-12);
  EXPECT_NEAR(distance_to(*cw.curve(), Vec3(10 / std::sqrt(2.0), -10 / std::sqrt(2.0), 0)), 0.0, 1e-6);
  // G18 (ZX): counter-clockwise about +Y turns Z towards X, so G2 (clockwise) turns X10 towards Z10
  EXPECT_NEAR(*b[5].length_mm(), 5 * pi, 1e-12);
  const Block& zx = b[5];
  expect_consistent(zx);
  EXPECT_NEAR(distance_to(*zx.curve(), Vec3(10 / std::sqrt(2.0), 0, 10 / std::sqrt(2.0))), 0.0, 1e-6);
  const Block& yz = b[7];
  expect_consistent(yz);
  EXPECT_NEAR(distance_to(*yz.curve(), Vec3(0, 10 / std::sqrt(2.0), -10 / std::sqrt(2.0))), 0.0, 1e-6);
}

TEST(GcodeReader, RFormLongArcFullCircleTurnsHelix) {
  const auto b = read("F100\nG0 X0 Y0\nG2 X10 Y0 R-5\nG3 X10 Y0 I5 J0\nG3 X10 Y0 I5 P3\nG2 X10 Y0 Z-6 I-5 P2\n");
  ASSERT_EQ(b.size(), 5u);
  EXPECT_NEAR(*b[1].length_mm(), 5 * pi, 1e-9);  // R-5 from (0,0) to (10,0): a half circle either way
  EXPECT_NEAR(*b[2].length_mm(), 10 * pi, 1e-9);  // full circle
  EXPECT_NEAR(*b[3].length_mm(), 30 * pi, 1e-9);  // three turns
  EXPECT_EQ(b[4].type, BlockType::helix);
  EXPECT_NEAR(*b[4].length_mm(), std::hypot(20 * pi, 6.0), 1e-9);
  for (std::size_t i = 1; i < b.size(); ++i) expect_consistent(b[i]);
  // R-form: the short arc (R > 0) and the long arc (R < 0) of the same chord
  const auto s = read("F100\nG0 X0 Y0\nG3 X10 Y0 R10\nG0 X0 Y0\nG3 X10 Y0 R-10\n");
  const double short_len = 10 * 2 * std::asin(0.5), long_len = 10 * (2 * pi - 2 * std::asin(0.5));
  EXPECT_NEAR(*s[1].length_mm(), short_len, 1e-9);
  EXPECT_NEAR(*s[3].length_mm(), long_len, 1e-9);
  // a radius mismatch inside the tolerance is accepted
  EXPECT_EQ(read("F1\nG0 X0 Y0\nG2 X10.004 Y0 I5\n").size(), 2u);
}

TEST(GcodeReader, TinyCamBamArcStaysTinyNotAFullCircle) {
  // CamBam writes arcs of 0.1 um (issue 13): counter-clockwise from X24.3929 to X24.3928 about a
  // centre 0.5 mm away. A full circle is made only where the end is the start as computed (as in
  // LinuxCNC); within 1e-4 mm it used to be a 3.14 mm loop, an unprogrammed gouge.
  const auto b = read("G21 G17 F600\nG0 X24.3929 Y104.2273\nG3 X24.3928 I0.1128 J-0.4871\n");
  ASSERT_EQ(b.size(), 2u);
  EXPECT_LT(*b[1].length_mm(), 2e-4);
  EXPECT_GT(*b[1].length_mm(), 0.5e-4);
  expect_consistent(b[1]);
  // the same arc programmed back to its start is still a full circle
  const auto full = read("G21 G17 F600\nG0 X24.3929 Y104.2273\nG3 X24.3929 I0.1128 J-0.4871\n");
  EXPECT_NEAR(*full[1].length_mm(), 2 * pi * std::hypot(0.1128, 0.4871), 1e-9);
}


TEST(GcodeReader, ZeroOffsetAlongThePlaneNormalIsAccepted) {
  // FreeCAD's posts write K0.000 on G17 arcs; the controls accept it. K1 is refused (bad/).
  EXPECT_EQ(read("G21 G17 F600\nG0 X0 Y0\nG2 X10 Y0 Z0 I5 J0 K0.000\n").size(), 2u);
  EXPECT_EQ(read("G21 G18 F600\nG0 X0 Z0\nG2 X10 Z0 I5 K0 J0\n").size(), 2u);
}


TEST(GcodeReader, ArcRadiusToleranceIsLinuxCncs) {
  // Centre (r, 0): radius r to the start, r + d to the end (X 2r + d on the axis).
  auto arc = [](const std::string& units, double r, double end_x) {
    return read("F1 " + units + "\nG0 X0 Y0\nG2 X" + std::to_string(end_x) + " Y0 I" + std::to_string(r) + "\n");
  };
  EXPECT_EQ(arc("G21", 5, 10.028).size(), 2u);      // 0.028 mm <= 0.0283 mm
  EXPECT_THROW(arc("G21", 5, 10.029), InputError);  // 0.029 mm: over 0.0283 mm and over 0.1 % of 5 mm
  EXPECT_EQ(arc("G20", 0.5, 1.0028).size(), 2u);    // 0.0028 in <= 0.00283 in (inch program)
  EXPECT_THROW(arc("G20", 0.5, 1.0029), InputError);
  // a large radius: within 0.1 % of it (up to 100 times the absolute tolerance)
  EXPECT_EQ(arc("G21", 500, 1000.45).size(), 2u);       // 0.45 mm of 500 mm
  EXPECT_THROW(arc("G21", 500, 1000.55), InputError);   // 0.55 mm: over 0.1 %
  EXPECT_THROW(arc("G21", 5000, 10003.0), InputError);  // 3 mm: within 0.1 % but over 2.83 mm
}


TEST(GcodeReader, AbsoluteArcCentres) {
  const auto b = read("F100 G90.1\nG0 X20 Y10\nG3 X10 Y20 I10 J10\n");
  EXPECT_NEAR(*b[1].length_mm(), 5 * pi, 1e-12);
  EXPECT_NEAR(distance_to(*b[1].curve(), Vec3(10 + 10 / std::sqrt(2.0), 10 + 10 / std::sqrt(2.0), 0)), 0.0, 1e-6);
}

TEST(GcodeReader, WorkOffsetsG92AndRotation) {
  const auto b = read("G10 L2 P2 X100 Y50 Z0\nG55 G0 X1 Y2\nG54 G0 X1 Y2\nG92 X0 Y0\nG0 X1\nG92.1\n"
                      "G10 L2 P1 X0 Y0 R90\nG0 X10 Y0\nG53 G0 X3 Y4\n");
  ASSERT_EQ(b.size(), 5u);
  expect_near(b[0].end, Vec3(101, 52, 0));
  expect_near(b[1].end, Vec3(1, 2, 0));
  expect_near(b[2].end, Vec3(2, 2, 0));           // G92 made (1,2) the origin
  expect_near(b[3].end, Vec3(0, 10, 0), 1e-12);   // rotated by 90 degrees about Z
  expect_near(b[4].end, Vec3(3, 4, 0), 1e-12);    // G53: machine coordinates
  EXPECT_EQ(b[0].modal.work_offset, 2);
}

TEST(GcodeReader, FanucNurbsMatchesTheCurveItDescribes) {
  const auto b = read("G0 X-100 Y-60 Z0\nF100\nG06.2 P4 K0 X-100 Y-60 Z0 R1\nK0 X-100 Y0\nK0 X-40 Y70\nK0 X60 Y90\n"
                      "K0.5 X30 Y120\nK1\nK1\nK1\nK1\nG1 X0 Y0\n");
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[1].type, BlockType::nurbs);
  const auto& c = std::get<NurbsCurve>(b[1].geometry);
  EXPECT_EQ(c.degree(), 3);
  EXPECT_EQ(c.knots(), (std::vector<double>{0, 0, 0, 0, 0.5, 1, 1, 1, 1}));
  ASSERT_EQ(c.points().size(), 5u);
  expect_near(c.points()[2], Vec3(-40, 70, 0));
  expect_consistent(b[1]);
  EXPECT_NEAR(*b[1].length_mm(), 249.46310991070, 1e-8);  // seed example 1 (kontur spline)
  EXPECT_EQ(b[1].location.line, 3);
  EXPECT_EQ(b[2].type, BlockType::line);
  expect_near(b[2].start, Vec3(30, 120, 0));
}

TEST(GcodeReader, LinuxcncG62WithClosingBlocksAndQ) {
  Reader r("t.ngc", "G0 X0 Y0\nF100\nG6.2 X0 Y0 R1 K0 P3 Q1\nX1 Y1 R2 K0\nX2 Y0 R1 K0\nX3 Y1 R1 K1\nG6.2 K2\nG6.2 K2\nG6.2 K2\nM2\n");
  Block b;
  ASSERT_TRUE(r.next(b));
  ASSERT_TRUE(r.next(b));
  EXPECT_EQ(b.type, BlockType::nurbs);
  const auto& c = std::get<NurbsCurve>(b.geometry);
  EXPECT_TRUE(c.rational());
  EXPECT_EQ(c.degree(), 2);
  expect_consistent(b);
  EXPECT_FALSE(r.next(b));
  ASSERT_EQ(r.warning_count(), 1u);
  EXPECT_NE(r.warnings()[0].find("true spline interpolation"), std::string::npos);
}

TEST(GcodeReader, LinuxcncG52UniformKnotsFromTheCurrentPosition) {
  const auto b = read("G0 X0 Y0\nF100\nG5.2 P1 L3\nX0 Y1 P1\nX2 Y2 P1\nX2 Y0 P1\nX0 Y0 P2\nG5.3\nG0 X5\n");
  ASSERT_EQ(b.size(), 3u);
  const auto& c = std::get<NurbsCurve>(b[1].geometry);
  EXPECT_EQ(c.points().size(), 5u);
  EXPECT_EQ(c.knots(), (std::vector<double>{0, 0, 0, 1, 2, 3, 3, 3}));
  EXPECT_DOUBLE_EQ(c.weights()[4], 2.0);
  expect_consistent(b[1]);
}

TEST(GcodeReader, BeziersAndTangentContinuation) {
  const auto b = read("G0 X0 Y0\nF100\nG5 X10 Y0 I2 J3 P-2 Q3\nG5 X20 Y0 P-2 Q-3\nG5.1 X30 Y0 I5 J5\n");
  ASSERT_EQ(b.size(), 4u);
  for (int i = 1; i <= 3; ++i) {
    EXPECT_EQ(b[static_cast<std::size_t>(i)].type, BlockType::bezier);
    expect_consistent(b[static_cast<std::size_t>(i)]);
  }
  const auto& first = std::get<NurbsCurve>(b[1].geometry);
  const auto& second = std::get<NurbsCurve>(b[2].geometry);
  EXPECT_EQ(first.degree(), 3);
  expect_near(first.points()[1], Vec3(2, 3, 0));
  expect_near(first.points()[2], Vec3(8, 3, 0));
  expect_near(second.points()[1], Vec3(12, -3, 0));  // reflection of the previous second control point
  // tangent continuity at the joint
  const Vec3 t1 = first.derivatives(first.u_max(), 1)[1].normalized();
  const Vec3 t2 = second.derivatives(second.u_min(), 1)[1].normalized();
  expect_near(t1, t2, 1e-12);
  EXPECT_EQ(std::get<NurbsCurve>(b[3].geometry).degree(), 2);
}

TEST(GcodeReader, CircleThroughAnIntermediatePoint) {
  const double h = 10 / std::sqrt(2.0);
  const auto b = read("G0 X10 Y0 Z0\nF100\nCIP X0 Y10 Z0 I1=" + std::to_string(h) + " J1=" + std::to_string(h) +
                      " K1=0\nG0 X10 Y0 Z0\nG02.4 X0 Y0 Z10\nX-10 Y0 Z0\nG0 X0 Y0 Z0\nG91 CIP X10 Y10 I1=5 J1=10\n");
  ASSERT_EQ(b.size(), 6u);
  const Block& cip = b[1];
  EXPECT_EQ(cip.type, BlockType::circle_3d);
  EXPECT_EQ(cip.via_count, 1);
  EXPECT_NEAR(*cip.length_mm(), 5 * pi, 1e-6);
  expect_consistent(cip, 1e-6);
  EXPECT_NEAR(distance_to(*cip.curve(), cip.via[0]), 0.0, 1e-6);
  const Block& fanuc = b[3];  // half circle in the XZ plane through (0, 0, 10)
  EXPECT_EQ(fanuc.type, BlockType::circle_3d);
  EXPECT_EQ(fanuc.location.line, 5);
  EXPECT_NEAR(*fanuc.length_mm(), 10 * pi, 1e-9);
  EXPECT_NEAR(distance_to(*fanuc.curve(), Vec3(0, 0, 10)), 0.0, 1e-6);
  expect_consistent(fanuc);
  const Block& inc = b[5];  // incremental: I1= J1= relative to the start, missing K1= = start's Z
  expect_near(inc.via[0], Vec3(5, 10, 0));
  expect_consistent(inc);
}

TEST(GcodeReader, ConicBlockThroughItsFivePoints) {
  const auto b = read("G0 X0 Y0 Z0\nF100\nCONIC X10 Y0 Z0 I1=1 J1=3 K1=0 I2=5 J2=4 K2=0 I3=9 J3=3 K3=0\nG1 X0\n");
  ASSERT_EQ(b.size(), 3u);
  const Block& c = b[1];
  EXPECT_EQ(c.type, BlockType::conic);
  ASSERT_NE(c.curve(), nullptr);
  expect_consistent(c, 1e-9);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(distance_to(*c.curve(), c.via[static_cast<std::size_t>(i)]), 0.0, 1e-3);
  EXPECT_GT(*c.length_mm(), 12.0);
  EXPECT_EQ(c.via_count, 3);
  expect_near(c.via[1], Vec3(5, 4, 0));
  expect_near(c.end, Vec3(10, 0, 0));
  expect_near(b[2].start, Vec3(10, 0, 0));
}

TEST(GcodeReader, CannedCyclesExpandIntoMoves) {
  // G81 with G98: from Z10, R2, bottom -5, two holes
  auto b = read("G17 G21 G90 F100\nG0 X0 Y0 Z10\nG98 G81 X5 Y0 Z-5 R2\nX10\nG80\n");
  ASSERT_EQ(b.size(), 1u + 4u + 4u);
  EXPECT_EQ(b[1].canned_cycle, 81);
  expect_near(b[1].end, Vec3(5, 0, 10));   // rapid XY at the initial Z
  expect_near(b[2].end, Vec3(5, 0, 2));    // rapid to R
  EXPECT_EQ(b[3].type, BlockType::line);
  expect_near(b[3].end, Vec3(5, 0, -5));   // feed to the bottom
  expect_near(b[4].end, Vec3(5, 0, 10));   // G98: back to the initial Z
  expect_near(b[8].end, Vec3(10, 0, 10));
  // G99 retracts to R; G82 dwells at the bottom
  b = read("F100\nG0 X0 Y0 Z10\nG99 G82 X5 Z-5 R2 P0.5\n");
  ASSERT_EQ(b.size(), 6u);
  EXPECT_EQ(b[4].type, BlockType::dwell);
  EXPECT_DOUBLE_EQ(b[4].dwell_s, 0.5);
  expect_near(b[5].end, Vec3(5, 0, 2));
  // G83 pecks of 2 mm from R2 to -3: feeds to 0, -2, -3 with full retracts
  b = read("F100\nG0 X0 Y0 Z10\nG83 X0 Z-3 R2 Q2\n");
  std::vector<double> feed_depths;
  for (const auto& x : b)
    if (x.type == BlockType::line) feed_depths.push_back(x.end.z());
  EXPECT_EQ(feed_depths, (std::vector<double>{0, -2, -3}));
  // G73 chip breaking: small retracts only
  b = read("F100\nG0 X0 Y0 Z10\nG73 X0 Z-3 R2 Q2\n");
  double highest_after_first_feed = -1e9;
  bool fed = false;
  for (const auto& x : b) {
    if (x.type == BlockType::line) fed = true;
    else if (fed && &x != &b.back()) highest_after_first_feed = std::max(highest_after_first_feed, x.end.z());
  }
  EXPECT_LT(highest_after_first_feed, 2.0);
  expect_near(b.back().end, Vec3(0, 0, 10));
  // incremental with L repeats
  b = read("F100\nG0 X0 Y0 Z10\nG91 G81 X10 Z-5 R-8 L3\n");
  expect_near(b.back().end, Vec3(30, 0, 10));
}

TEST(GcodeReader, DwellInverseTimeAndModalState) {
  const auto b = read("G93\nG1 X10 F2\nG4 P1.5\nG94 F300 M3 S1200 M8 G64 P0.01 Q0.02 G43 H3\nG1 X20\nG61 G1 X30\n");
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[0].feed.mode, FeedMode::inverse_time);
  EXPECT_DOUBLE_EQ(b[0].feed.duration_s(), 30.0);
  EXPECT_EQ(b[1].type, BlockType::dwell);
  EXPECT_DOUBLE_EQ(b[1].dwell_s, 1.5);
  const ModalState& m = b[2].modal;
  EXPECT_EQ(m.spindle, SpindleState::clockwise);
  EXPECT_DOUBLE_EQ(m.spindle_rpm, 1200.0);
  EXPECT_TRUE(m.flood);
  EXPECT_DOUBLE_EQ(m.blend_tolerance_mm, 0.01);
  EXPECT_DOUBLE_EQ(m.naive_cam_tolerance_mm, 0.02);
  EXPECT_TRUE(m.tool_length_offset);
  EXPECT_EQ(m.tool_length_h, 3);
  EXPECT_EQ(b[3].modal.path_control, PathControl::exact_path);
}

TEST(GcodeReader, ParametersAssignedAfterTheLine) {
  const auto b = read("#1=2 #2=[#1+1]\nF100\nG1 X#1 Y#2\n#<_scale> = 3.0\n#<x> = [#<_scale> * 2]\nG1 X#<x> Y[#<X> ** 2]\n");
  ASSERT_EQ(b.size(), 2u);
  expect_near(b[0].end, Vec3(2, 1, 0));  // #2 = old #1 (0) + 1
  expect_near(b[1].end, Vec3(6, 36, 0));
}

TEST(GcodeReader, BlockDeleteSwitch) {
  const std::string p = "F100\n/G1 X5\nG1 Y5\n";
  EXPECT_EQ(read(p).size(), 1u);
  ReaderOptions o;
  o.block_delete = false;
  EXPECT_EQ(read(p, o).size(), 2u);
}

TEST(GcodeReader, ProgramEndsAtM2AndWarnsWithoutIt) {
  Reader r("t.ngc", "F100\nG1 X1\nM2\nG1 X2\n");
  Block b;
  int n = 0;
  while (r.next(b)) ++n;
  EXPECT_EQ(n, 1);
  EXPECT_EQ(r.warning_count(), 0u);
  Reader r2("t.ngc", "F100\nG1 X1\n");
  while (r2.next(b)) {
  }
  EXPECT_EQ(r2.warning_count(), 1u);
}

TEST(GcodeReader, UnusedWordsWarnAndTheRunGoesOn) {
  Reader r("t.ngc", "F100\nG1 X10 R5\nG96 S100 M3\nM2\n");
  Block b;
  int n = 0;
  while (r.next(b)) ++n;
  EXPECT_EQ(n, 1);
  ASSERT_EQ(r.warning_count(), 2u);
  EXPECT_EQ(r.warnings()[0], "t.ngc:2:8: warning: R5: not used by any code of this block (ignored)");
  EXPECT_NE(r.warnings()[1].find("G96: constant surface speed is recorded"), std::string::npos);
}

TEST(GcodeReader, MachineSpecificMCodesWarnOnceAndAreIgnored) {
  // M25, M40, M75 (Haas, Fanuc posts), M101 (a user M code): they do not move the axes (issue 13).
  Reader r("t.ngc", "G21 F100\nM25\nG1 X10 M40\nM25\nM101\nM101\nG1 X20\nM2\n");
  Block b;
  int n = 0;
  while (r.next(b)) ++n;
  EXPECT_EQ(n, 2);
  ASSERT_EQ(r.warning_count(), 3u);  // once per code
  EXPECT_EQ(r.warnings()[0],
            "t.ngc:2:1: warning: M25: machine-specific M code, ignored (it does not move the axes; warned once)");
  EXPECT_NE(r.warnings()[1].find("M40: machine-specific M code"), std::string::npos);
  EXPECT_NE(r.warnings()[2].find("M101: user M code"), std::string::npos);
}


TEST(GcodeReader, FanucAndHaasProgramNumbersAreTheProgramsName) {
  // The headers of Fanuc and Haas programs (issue 13: 27 real programs stopped there).
  // LinuxCNC's reading tolerates them (detected, such a program gets the Fanuc reading:
  // test_gcode_fanuc_dialect.cpp).
  ReaderOptions linuxcnc;
  linuxcnc.dialect = Dialect::linuxcnc;
  for (const char* header : {"%\nO1234 (TEST PART)\n", "%O1200(NAME)\n", ":0097\n", "O01023 (NAME)\n"}) {
    Reader r("t.ngc", std::string(header) + "G21 G90 F100\nG1 X10\nM30\n%\n", linuxcnc);
    Block b;
    int n = 0;
    while (r.next(b)) ++n;
    EXPECT_EQ(n, 1) << header;
    ASSERT_EQ(r.warning_count(), 1u) << header;
    EXPECT_NE(r.warnings()[0].find("a program number (Fanuc, Haas)"), std::string::npos) << header;
  }
  // LinuxCNC O-words keep their meaning, and '%' is followed by nothing else
  EXPECT_NE(error_of("o100 fly\n"), "");
  EXPECT_NE(error_of("%G1 X1\n").find("or be followed by a program number"), std::string::npos);
}


TEST(GcodeReader, NothingAfterAnError) {
  Reader r("t.ngc", "F100\nG1 X1\nG1 X[1/0]\nG1 X3\n");
  Block b;
  ASSERT_TRUE(r.next(b));
  EXPECT_THROW(r.next(b), InputError);
  EXPECT_FALSE(r.next(b));
}

TEST(GcodeReader, OWordSubroutineWithArgumentsAndReturnValue) {
  const auto b = read("F100\no<square> sub\nG1 X#1 Y0\nG1 Y#1\no<square> endsub [#1 * 2]\n#1 = 7\n"
                      "o<square> call [3]\nG1 X#1 Y#<_value>\no<square> call [5]\nM2\n");
  ASSERT_EQ(b.size(), 5u);
  expect_near(b[0].end, Vec3(3, 0, 0));
  expect_near(b[1].end, Vec3(3, 3, 0));
  expect_near(b[2].end, Vec3(7, 6, 0));  // #1 restored after the call, #<_value> = 2 * 3
  expect_near(b[4].end, Vec3(5, 5, 0));
  EXPECT_EQ(b[0].location.line, 3);
}

TEST(GcodeReader, OWordLoopsAndConditionals) {
  // while with break, do-while, repeat with continue, if/elseif/else
  const auto b = read("F100\n#1=0\no1 while [#1 LT 10]\n#1=[#1+1]\no2 if [#1 EQ 4]\no1 break\no2 endif\nG1 X#1\n"
                      "o1 endwhile\n#2=0\no3 do\n#2=[#2+1]\nG1 Y#2\no3 while [#2 LT 2]\n"
                      "#3=0\no4 repeat [4]\n#3=[#3+1]\no5 if [#3 EQ 2]\no4 continue\no5 elseif [#3 EQ 3]\nG1 Z-3\n"
                      "o5 else\nG1 Z#3\no5 endif\no4 endrepeat\nM2\n");
  std::vector<double> xs, ys, zs;
  for (const auto& x : b) {
    xs.push_back(x.end.x());
    ys.push_back(x.end.y());
    zs.push_back(x.end.z());
  }
  ASSERT_EQ(b.size(), 3u + 2u + 3u);
  EXPECT_EQ(std::vector<double>(xs.begin(), xs.begin() + 3), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(std::vector<double>(ys.begin() + 3, ys.begin() + 5), (std::vector<double>{1, 2}));
  EXPECT_EQ(std::vector<double>(zs.begin() + 5, zs.end()), (std::vector<double>{1, -3, 4}));
}

TEST(GcodeReader, OWordEndlessLoopIsAnError) {
  ReaderOptions o;
  o.max_loop_iterations = 1000;
  std::string message;
  try {
    read("F100\no1 while [1]\nG1 X1\no1 endwhile\n", o);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_EQ(message, "test.ngc:2:1: O1: more than 1000 loop iterations and calls in the program (endless loop?) (dialect linuxcnc)");
  EXPECT_THROW(read("F100\no1 repeat [2000]\no1 endrepeat\n", o), InputError);
  EXPECT_THROW(read("o1 sub\no1 call\no1 endsub\no1 call\n", o), InputError);  // recursion
}

TEST(GcodeReader, OWordCallSeeksBackAcrossTheFileBuffer) {
  // the subroutine is more than the reader's 1 MiB buffer before the call
  const std::string path = ::testing::TempDir() + "kontur_oword_seek.ngc";
  {
    std::ofstream f(path);
    f << "F100\no100 sub\nG1 X#1\no100 endsub\n";
    const std::string comment = "(" + std::string(70, 'c') + ")\n";
    for (int i = 0; i < 20000; ++i) f << comment;
    f << "o100 call [1]\no100 call [2]\nM2\n";
  }
  Reader r(path);
  Block b;
  std::vector<double> xs;
  std::vector<long> lines;
  while (r.next(b)) {
    xs.push_back(b.end.x());
    lines.push_back(b.location.line);
  }
  EXPECT_EQ(xs, (std::vector<double>{1, 2}));
  EXPECT_EQ(lines, (std::vector<long>{3, 3}));
  EXPECT_EQ(r.lines_read(), 20007);
  std::remove(path.c_str());
}

#if defined(__GLIBC__)
// Streaming: the heap in use while a program is read does not grow with its length
// (10^6 blocks with expressions and parameter assignments; sampled every 10^4 blocks).
TEST(GcodeReader, HeapDoesNotGrowWithTheProgramsLength) {
  const std::string path = ::testing::TempDir() + "kontur_stream_1e6.ngc";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "G21 G90 F1000\n#<_y> = 0\n");
    for (int i = 0; i < 1000000; ++i) std::fprintf(f, "N%d G1 X%d.5 Y[#<_y> + 1] Z-1\n#<_y> = %d\n", i, i % 100, i % 7);
    std::fclose(f);
  }
  std::size_t heap_at_10k = 0, heap_max = 0;
  Reader reader(path);
  Block b;
  long blocks = 0;
  while (reader.next(b)) {
    if (++blocks % 10000 == 0) {
      const std::size_t used = mallinfo2().uordblks;
      if (blocks == 10000) heap_at_10k = used;
      heap_max = std::max(heap_max, used);
    }
  }
  EXPECT_EQ(blocks, 1000000);
  EXPECT_LT(heap_max - heap_at_10k, std::size_t{64} * 1024) << "heap grew from " << heap_at_10k << " to " << heap_max;
  std::remove(path.c_str());
}
#endif

// The two passes of for_each_block: a program whose blocks fit in gcode_kept_blocks_bytes is
// read once and its kept blocks handed on; a longer one is read again (its kept blocks dropped, the
// memory bounded). Either way the second pass hands on the blocks a fresh reading gives.
TEST(GcodeReader, ValidatedBlocksAreKeptWithinTheirMemoryBoundAndReadAgainBeyond) {
  const std::string path = ::testing::TempDir() + "kontur_validated.ngc";
  const auto write = [&](int lines) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "G21 G90 F1000\n");
    for (int i = 0; i < lines; ++i) std::fprintf(f, "G1 X%d.25 Y%d\n", i % 100, i % 7);
    std::fprintf(f, "G5.2 X0 Y0 L3\nX10 Y10\nX20 Y0\nX30 Y10\nG5.3\nM2\n");  // and a spline
    std::fclose(f);
  };
  const auto same_as_a_fresh_reading = [&](const ValidatedProgram& v) {
    std::vector<Block> fresh;
    Reader r(path, v.options);
    Block b;
    while (r.next(b)) fresh.push_back(b);
    std::size_t k = 0;
    for_each_validated_block(v, [&](const Block& handed) {
      ASSERT_LT(k, fresh.size());
      EXPECT_EQ(handed.location.line, fresh[k].location.line);
      EXPECT_EQ(handed.end, fresh[k].end);
      EXPECT_EQ(handed.geometry.index(), fresh[k].geometry.index());
      ++k;
    });
    EXPECT_EQ(k, fresh.size());
  };
  write(1000);
  const ValidatedProgram small = validate_program(path);
  EXPECT_TRUE(small.kept_blocks);
  EXPECT_EQ(small.blocks.size(), 1001u);
  same_as_a_fresh_reading(small);
  // More blocks than the bound holds (each takes at least sizeof(Block)).
  write(static_cast<int>(tolerances::gcode_kept_blocks_bytes / sizeof(Block)) + 100);
  const ValidatedProgram large = validate_program(path);
  EXPECT_FALSE(large.kept_blocks);
  EXPECT_TRUE(large.blocks.empty());
  same_as_a_fresh_reading(large);
  std::remove(path.c_str());
}

TEST(GcodeExpression, OperatorsFunctionsAndPrecedence) {
  ParameterTable p;
  p.set_named("XSCALE", 2.0);
  p.set_numbered(5, 4.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("[1 + 2 * 3]", p), 7.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("[2 ** 3 ** 2]", p), 64.0);  // left-associative as LinuxCNC
  EXPECT_DOUBLE_EQ(evaluate_expression("[7 MOD 3]", p), 1.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("[-7 MOD 3]", p), 2.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("[#<xscale> * 53.]", p), 106.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("[#5 GT 3 AND #5 LT 5]", p), 1.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("[1 EQ 2 OR 0 XOR 1]", p), 1.0);
  EXPECT_NEAR(evaluate_expression("SIN[30]", p), 0.5, 1e-15);
  EXPECT_NEAR(evaluate_expression("[COS[60] + TAN[45]]", p), 1.5, 1e-15);
  EXPECT_NEAR(evaluate_expression("ATAN[1]/[1]", p), 45.0, 1e-13);
  EXPECT_NEAR(evaluate_expression("[ASIN[1] + ACOS[0]]", p), 180.0, 1e-13);
  EXPECT_DOUBLE_EQ(evaluate_expression("SQRT[16]", p), 4.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("ABS[-3]", p), 3.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("ROUND[2.5]", p), 3.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("FIX[-2.5]", p), -3.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("FUP[2.1]", p), 3.0);
  EXPECT_NEAR(evaluate_expression("LN[EXP[2]]", p), 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(evaluate_expression("EXISTS[#<xscale>]", p), 1.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("EXISTS[#<nope>]", p), 0.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("-#5", p), -4.0);
  EXPECT_DOUBLE_EQ(evaluate_expression("##[2+3]", p), 0.0);  // #4 (the value of #5) was never set
  EXPECT_THROW((void)evaluate_expression("[1/0]", p), InputError);
  EXPECT_THROW((void)evaluate_expression("[LN[0]]", p), InputError);
  EXPECT_THROW((void)evaluate_expression("[10 ** 400]", p), InputError);
  EXPECT_THROW((void)evaluate_expression("#<undefined>", p), InputError);
  EXPECT_THROW((void)evaluate_expression("[1 + ]", p), InputError);
  EXPECT_THROW((void)evaluate_expression("[1] 2", p), InputError);
}

TEST(GcodeReader, ErrorsNameLineColumnAndWord) {
  EXPECT_EQ(error_of("F100\nG1 X1\n  G1 X[#<a>]\n"), "test.ngc:3:8: #<A>: undefined parameter (dialect linuxcnc)");
  EXPECT_EQ(error_of("G0 X0 Y0\nF1\nG06.2 P4 K0 X0 Y0\nK0 X1 Y0\nK0 X1 Y1\nK0 X2 Y1\nK1 X3 Y1\nK2 X4 Y0\nK2\nK2\nK2\n"),
            "test.ngc:3:1: G06.2: 9 knots given, 10 needed (6 control points + rank 4) (dialect linuxcnc)");
}

// Regression: an arc whose end lies within the radius tolerance but off its circle (here 2.54 um,
// from LinuxCNC's arc-arc-neartangent.ngc) ended on the circle, and the next move started 2.54 um
// away: a jump of 33 times the jerk limit in one servo period. It is now a slight spiral that ends
// exactly at the programmed point, with its radius going linearly from start to end.
TEST(GcodeReader, ArcWithinTheRadiusToleranceEndsExactlyAtItsEndPoint) {
  const auto blocks = read("G20 G90 G17\nG0 X.2 Y.1\nG2 X.2999 Y0 I0 J-.1 F10\nG1 X1\n");
  ASSERT_EQ(blocks.size(), 3u);
  const auto& arc = std::get<HelixArc>(blocks[1].geometry);
  const Vec3 end(0.2999 * 25.4, 0.0, 0.0);
  EXPECT_LE((arc.point(arc.u_max()) - end).norm(), 1e-12);
  const Curve& next = *blocks[2].curve();
  EXPECT_LE((arc.point(arc.u_max()) - next.point(next.u_min())).norm(), 1e-12);
  EXPECT_NEAR(arc.radius_mm(), 0.1 * 25.4, 1e-12);
  EXPECT_NEAR(arc.radius_change_mm(), -0.0001 * 25.4, 1e-12);
  // The radius changes linearly with the angle: halfway, halfway between.
  EXPECT_NEAR((arc.point(0.5) - arc.frame().centre).norm(), (0.1 - 0.00005) * 25.4, 1e-12);
}

}  // namespace
}  // namespace kontur::gcode
