// The extra axes A B C [deg] and U V W [mm] in the G-code reader (issue 14): absolute and
// incremental words, units, a move of the extra axes alone, arcs, work offsets and G92, G28, G53,
// the dialects, and the refusals where an extra axis cannot move.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>

#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

std::vector<Block> read(const std::string& program, std::optional<Dialect> dialect = std::nullopt,
                        const std::string& name = "axes.ngc") {
  ReaderOptions options;
  options.dialect = dialect;
  Reader reader(name, program, options);
  std::vector<Block> blocks;
  Block b;
  while (reader.next(b)) blocks.push_back(b);
  return blocks;
}

std::string error_of(const std::string& program, std::optional<Dialect> dialect = std::nullopt,
                     const std::string& name = "axes.ngc") {
  try {
    read(program, dialect, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A B C U V W
ExtraAxes xa(double a, double b = 0, double c = 0, double u = 0, double v = 0, double w = 0) { return {a, b, c, u, v, w}; }

void expect_extra(const ExtraAxes& got, const ExtraAxes& want) {
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], want[i], 1e-12) << extra_axis_letters[i];
}

TEST(GcodeExtraAxes, AbsoluteAndIncrementalWords) {
  const auto b = read("G21 G90 F600\nG1 X10 A30 W5\nG91 G1 X10 A15 W-2\nG0 B10\nM2\n");
  ASSERT_EQ(b.size(), 3u);
  expect_extra(b[0].extra_start, xa(0));
  expect_extra(b[0].extra_end, xa(30, 0, 0, 0, 0, 5));
  expect_extra(b[1].extra_start, xa(30, 0, 0, 0, 0, 5));
  expect_extra(b[1].extra_end, xa(45, 0, 0, 0, 0, 3));
  EXPECT_EQ(b[2].type, BlockType::rapid);
  expect_extra(b[2].extra_end, xa(45, 10, 0, 0, 0, 3));
  EXPECT_TRUE(b[2].moves_extra_axes());
}

TEST(GcodeExtraAxes, InchScalesUVWButNotTheAngles) {
  const auto b = read("G20 G90 F10\nG1 X1 U1 V2 W-1 A90 C-45\nM2\n");
  ASSERT_EQ(b.size(), 1u);
  EXPECT_NEAR(b[0].end.x(), 25.4, 1e-12);
  expect_extra(b[0].extra_end, xa(90, 0, -45, 25.4, 50.8, -25.4));
}

TEST(GcodeExtraAxes, AMoveAloneIsALineOfZeroLength) {
  const auto b = read("G90 F600\nG1 X5 Y6 Z7\nG1 A90\nG0 W3\nG1 X5\nM2\n");
  ASSERT_EQ(b.size(), 4u);
  for (int i : {1, 2}) {
    EXPECT_EQ(b[static_cast<std::size_t>(i)].start, b[static_cast<std::size_t>(i)].end);
    EXPECT_DOUBLE_EQ(*b[static_cast<std::size_t>(i)].length_mm(), 0.0);
    EXPECT_TRUE(b[static_cast<std::size_t>(i)].moves_extra_axes());
  }
  EXPECT_EQ(b[1].type, BlockType::line);
  EXPECT_DOUBLE_EQ(b[1].feed.value, 600.0);
  EXPECT_EQ(b[1].start, Vec3(5, 6, 7));
  expect_extra(b[1].extra_end, xa(90));
  EXPECT_EQ(b[2].type, BlockType::rapid);
  expect_extra(b[2].extra_end, xa(90, 0, 0, 0, 0, 3));
  // nothing moves: a zero-length line as before, extra axes still
  EXPECT_FALSE(b[3].moves_extra_axes());
  expect_extra(b[3].extra_start, xa(90, 0, 0, 0, 0, 3));
}

TEST(GcodeExtraAxes, ArcsAndHelicesCarryTheExtraAxesAlong) {
  const auto b = read("G17 G90 F600\nG0 X10 Y0\nG3 X0 Y10 I-10 J0 A90 U2\nG2 X10 Y0 Z-1 R10 B5\nM2\n");
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[1].type, BlockType::arc);
  expect_extra(b[1].extra_start, xa(0));
  expect_extra(b[1].extra_end, xa(90, 0, 0, 2));
  EXPECT_EQ(b[2].type, BlockType::helix);
  expect_extra(b[2].extra_end, xa(90, 5, 0, 2));
}

TEST(GcodeExtraAxes, WorkOffsetsAndG92AreTranslations) {
  // G10 L2 P1 A10 W1: the G54 offset; the program's A0 is machine A10. The rotation R acts on X Y only.
  const auto b = read("G21 G90 F600\nG10 L2 P1 A10 W1 R90\nG54 G1 A0 W0\nG1 A5 W2\n"
                      "G92 A0 W0\nG1 A1\nG92.1\nG1 A1\nG10 L20 P1 A0\nG1 A2\nM2\n");
  ASSERT_EQ(b.size(), 5u);
  expect_extra(b[0].extra_end, xa(10, 0, 0, 0, 0, 1));
  expect_extra(b[1].extra_end, xa(15, 0, 0, 0, 0, 3));
  // G92 A0 W0 at A15 W3 (machine): program A1 is machine 16
  expect_extra(b[2].extra_end, xa(16, 0, 0, 0, 0, 3));
  // G92.1: no G92 offset: program A1 is machine 11
  expect_extra(b[3].extra_end, xa(11, 0, 0, 0, 0, 3));
  // G10 L20 P1 A0: here (machine A11) is A0; A2 is machine 13
  expect_extra(b[4].extra_end, xa(13, 0, 0, 0, 0, 3));
  EXPECT_NEAR(b[4].end.x(), 0.0, 1e-12);
}

TEST(GcodeExtraAxes, G92SavedAndRestored) {
  const auto b = read("G90 F600\nG1 A10\nG92 A0\nG92.2\nG1 A1\nG92.3\nG1 A1\nM2\n");
  ASSERT_EQ(b.size(), 3u);
  expect_extra(b[1].extra_end, xa(1));
  expect_extra(b[2].extra_end, xa(11));
}

TEST(GcodeExtraAxes, G28GoesThroughTheIntermediatePointHomeAndG53) {
  const auto b = read("G90 F600\n#5164=45\n#5169=2\nG1 X1 A10 W1\nG28 A20\nG28\nG53 G0 A-5\nM2\n");
  ASSERT_EQ(b.size(), 5u);
  expect_extra(b[1].extra_end, xa(20, 0, 0, 0, 0, 1));  // the intermediate point
  expect_extra(b[2].extra_end, xa(45, 0, 0, 0, 0, 1));  // home, for A only
  EXPECT_EQ(b[2].start, b[2].end);
  expect_extra(b[3].extra_end, xa(45, 0, 0, 0, 0, 2));  // G28 alone: every axis home
  EXPECT_EQ(b[3].end, Vec3::Zero());
  EXPECT_EQ(b[4].type, BlockType::rapid);  // G53: machine coordinates
  expect_extra(b[4].extra_end, xa(-5, 0, 0, 0, 0, 2));
}

TEST(GcodeExtraAxes, WorkSystemsSwitchAndG53IgnoresThem) {
  // G55's C offset 100; G53 C5 is machine C5 whatever the work system; G91 G28 C0 (Fanuc's way)
  // homes C through the current point
  const auto b = read("G90 F600\nG10 L2 P2 C100 U-1\nG55 G1 C10 U1\nG53 G0 C5\nG1 C20\nG54 G1 C20\n"
                      "G91 G28 C0\nG90\nM2\n");
  ASSERT_EQ(b.size(), 6u);
  expect_extra(b[0].extra_end, xa(0, 0, 110, 0));  // U: program 1, offset -1, machine 0
  expect_extra(b[1].extra_end, xa(0, 0, 5, 0));
  expect_extra(b[2].extra_end, xa(0, 0, 120, 0));
  expect_extra(b[3].extra_end, xa(0, 0, 20, 0));
  expect_extra(b[4].extra_end, xa(0, 0, 20, 0));  // the intermediate point: G91 C0, no motion
  expect_extra(b[5].extra_end, xa(0));            // home (#5166 = 0)
}

TEST(GcodeExtraAxes, InverseTimeMoveOfAnExtraAxisAlone) {
  const auto b = read("G93\nG1 A90 F2\nG94\nM2\n");
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b[0].feed.duration_s(), 30.0);
  expect_extra(b[0].extra_end, xa(90));
}

TEST(GcodeExtraAxes, DwellsAndCyclesKeepThemStill) {
  const auto b = read("G90 G17 F600\nG1 A30\nG4 P1\nG81 X1 Y1 Z-1 R1\nG80\nM2\n");
  ASSERT_GE(b.size(), 3u);
  for (std::size_t i = 1; i < b.size(); ++i) {
    expect_extra(b[i].extra_start, xa(30));
    expect_extra(b[i].extra_end, xa(30));
  }
}

TEST(GcodeExtraAxes, UnitsOfTheRangeCheck) {
  EXPECT_NE(error_of("G1 F1 W2000000\nM2\n").find(":1:7: W2e+06: beyond the supported range +-1e+06"), std::string::npos);
  EXPECT_EQ(error_of("G1 F1 A2000000\nM2\n"), "");  // an angle: many turns
}

TEST(GcodeExtraAxes, FanucAndHaasMillProgramsTurnA) {
  const auto b = read("%\nO1000\nG90 G54 G17\nG0 X0 Y0 A0\nG1 X10. A90. F100.\nG91 A-45.\nM30\n%\n", Dialect::fanuc);
  ASSERT_EQ(b.size(), 3u);
  expect_extra(b[1].extra_end, xa(90));
  expect_extra(b[2].extra_end, xa(45));
  const auto h = read("%\nO1000\nG90 G54\nG0 X0 B30.\nM30\n%\n", Dialect::haas);
  ASSERT_EQ(h.size(), 1u);
  expect_extra(h[0].extra_end, xa(0, 30));
}

TEST(GcodeExtraAxes, FanucAngleWithoutADecimalPointWarnsInDegrees) {
  ReaderOptions options;
  options.dialect = Dialect::fanuc;
  Reader reader("w.nc", "%\nO1\nG90 G21\nG0 X1. A90\nM30\n%\n", options);
  Block b;
  while (reader.next(b)) {
  }
  ASSERT_EQ(reader.warnings().size(), 1u);
  EXPECT_NE(reader.warnings()[0].find("A90: written without a decimal point, read as 90 deg; a fanuc with parameter "
                                      "3401#0 DPI=0 reads it as 90 least increments (0.09 deg)"),
            std::string::npos)
      << reader.warnings()[0];
}

TEST(GcodeExtraAxes, SinumerikAxisWords) {
  const auto b = read("G90 G17 F500\nG1 X10 A=90 C=IC(10)\nG0 U5\nM30\n", Dialect::sinumerik, "axes.mpf");
  ASSERT_EQ(b.size(), 2u);
  expect_extra(b[0].extra_end, xa(90, 0, 10));
  expect_extra(b[1].extra_end, xa(90, 0, 10, 5));
}

TEST(GcodeExtraAxes, SinumerikTransShiftsThemAndRotLeavesThem) {
  const auto b = read("G90 G17 G71 F500\nTRANS X1 A10 W2\nG1 A0 W0\nATRANS A5\nG1 A0\nROT RPL=90\nG1 A0\n"
                      "TRANS\nG1 A1\nM30\n",
                      Dialect::sinumerik, "trans.mpf");
  ASSERT_EQ(b.size(), 4u);
  expect_extra(b[0].extra_end, xa(10, 0, 0, 0, 0, 2));
  expect_extra(b[1].extra_end, xa(15, 0, 0, 0, 0, 2));
  // ROT (absolute) replaces the whole frame, TRANS A10 W2 too (W stays where it is: machine 2)
  expect_extra(b[2].extra_end, xa(0, 0, 0, 0, 0, 2));
  expect_extra(b[3].extra_end, xa(1, 0, 0, 0, 0, 2));
}

TEST(GcodeExtraAxes, GrblAndMach3TurnA) {
  const auto g = read("G21 G90\nG1 X1 A10 F100\n", Dialect::grbl, "axes.nc");
  ASSERT_EQ(g.size(), 1u);
  expect_extra(g[0].extra_end, xa(10));
  const auto m = read("G21 G90\nG1 X1 A10 F100\nM30\n", Dialect::mach3, "axes.tap");
  ASSERT_EQ(m.size(), 1u);
  expect_extra(m[0].extra_end, xa(10));
}

TEST(GcodeExtraAxes, RefusedWhereTheyCannotMove) {
  // a NURBS control point, a Bezier, a canned cycle, a 3-D circle, a frame
  EXPECT_EQ(error_of("G21 F100\nG5.2 X0 Y1 P1 L3\nX1 Y1 A5\nX1 Y0\nG5.3\nM2\n"),
            "axes.ngc:3:7: G5.2 A5: extra axes (A B C U V W) are not supported in a spline: its control points are X "
            "Y Z (move the extra axes in a block of their own) (dialect linuxcnc)");
  EXPECT_EQ(error_of("G21 F100\nG5.2 X0 Y1 A1 P1 L3\nX1 Y0\nG5.3\nM2\n"),
            "axes.ngc:2:12: G5.2 A1: extra axes (A B C U V W) are not supported in a spline: its control points are X "
            "Y Z (move the extra axes in a block of their own) (dialect linuxcnc)");
  EXPECT_NE(error_of("G21 F100\nG5 X1 Y1 I0 J1 P1 Q0 B2\nM2\n").find(":2:22: G5 B2: extra axes (A B C U V W) are not "
                                                                      "supported in a spline"),
            std::string::npos);
  EXPECT_NE(error_of("G21 F100\nG81 X1 Y1 Z-1 R1 A10\nM2\n").find(":2:18: G81 A10: extra axes (A B C U V W) are not "
                                                                    "supported in a canned cycle"),
            std::string::npos);
  EXPECT_NE(error_of("G1 F100\nCIP X10 Y0 I1=5 J1=5 A10\nM30\n", Dialect::sinumerik, "cip.mpf")
                .find("cip.mpf:2:22: CIP A10: extra axes (A B C U V W) are not supported in a circle or conic"),
            std::string::npos);
  EXPECT_NE(error_of("%\nO1\nG1 F100\nG02.4 X5 Y5 Z0 A1\nX10 Y0 Z0\nM30\n%\n", Dialect::fanuc)
                .find(":4:16: G02.4 A1: extra axes (A B C U V W) are not supported in a circle or conic"),
            std::string::npos);
  EXPECT_NE(error_of("ROT Z90 A10\nM30\n", Dialect::sinumerik, "frame.mpf")
                .find("frame.mpf:1:9: ROT A10: extra axes (A B C U V W) are not supported in a frame instruction"),
            std::string::npos);
  // Sinumerik's modulo positioning of a rotary axis
  EXPECT_NE(error_of("G0 A=DC(90)\nM30\n", Dialect::sinumerik, "dc.mpf").find(":1:4: A=DC(..): positioning a rotary axis"),
            std::string::npos);
  // U V W are a Fanuc lathe's incremental X Y Z
  EXPECT_NE(error_of("%\nO1\nG0 X10. Z1.\nG1 U-4.6 Z0 F0.2\nM30\n%\n", Dialect::fanuc)
                .find(":4:4: U-4.6: a lathe's incremental X Y Z (U V W): lathe programs"),
            std::string::npos);
}

TEST(GcodeExtraAxes, UnusedWordWarningsCountThemUsed) {
  Reader reader("w.ngc", "G90 F600\nG1 X1 A2 W3\nG92 B1\nM2\n");
  Block b;
  while (reader.next(b)) {
  }
  EXPECT_EQ(reader.warning_count(), 0u);
}

}  // namespace
}  // namespace kontur::gcode
