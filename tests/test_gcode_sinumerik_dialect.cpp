// The Sinumerik 840D dialect: R parameters and DEF variables with the control's expressions,
// labels and GOTOF / GOTOB, IF / ELSE, WHILE, FOR, REPEAT, LOOP with the loop limit, subprograms of
// the same file, CR= arcs, AC / IC, the programmable frame (TRANS / ROT / MIRROR), the drilling
// cycles CYCLE81 / 82 / 83 (also MCALL), G4 F / S, G9, and the refusals with their messages.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

ReaderOptions sinumerik() {
  ReaderOptions o;
  o.dialect = Dialect::sinumerik;
  return o;
}

std::vector<Block> read(const std::string& program, ReaderOptions options = sinumerik()) {
  Reader reader("s.mpf", program, options);
  std::vector<Block> blocks;
  Block b;
  while (reader.next(b)) blocks.push_back(b);
  return blocks;
}

std::string error_of(const std::string& program, ReaderOptions options = sinumerik()) {
  try {
    read(program, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> warnings_of(const std::string& program) {
  Reader reader("s.mpf", program, sinumerik());
  Block b;
  while (reader.next(b)) {
  }
  return reader.warnings();
}

void expect_point(const Vec3& p, double x, double y, double z) {
  EXPECT_NEAR(p.x(), x, 1e-9);
  EXPECT_NEAR(p.y(), y, 1e-9);
  EXPECT_NEAR(p.z(), z, 1e-9);
}

TEST(GcodeSinumerik, RParametersDefVariablesAndArithmetic) {
  const auto b = read(
      "%_N_PART_MPF\n"
      ";$PATH=/_N_MPF_DIR\n"
      "DEF REAL DEPTH=2.5, W\n"
      "DEF INT COUNT=7\n"
      "N10 R1=36 R2=R1/4 R[R2-6]=1.5 ; R3 = 1.5\n"
      "N20 W=POT(3)+SQRT(16)*2 ; 17\n"
      "N30 G90 G1 F1000 X=R1+2 Y=(R2*2) Z=-DEPTH\n"
      "N40 X=W Y=COUNT DIV 2 Z=COUNT MOD 4\n"
      "N50 X=SIN(30)*10 Y=ATAN2(1,1) Z=ROUND(2.5)+TRUNC(-1.7)+MINVAL(3,4)+MAXVAL(1,2)\n"
      "N60 X=R3 Y=ABS(-2) Z=1+2*3-4/2\n"
      "M30\n");
  ASSERT_EQ(b.size(), 4u);
  expect_point(b[0].end, 38, 18, -2.5);
  expect_point(b[1].end, 17, 3, 3);
  expect_point(b[2].end, 5, 45, 3 - 1 + 3 + 2);
  expect_point(b[3].end, 1.5, 2, 5);
}

TEST(GcodeSinumerik, AddressesWithoutSpaces) {
  const auto b = read("N10G1X10Y-5.5F100\nN20G91X.5Z=-1\nM30\n");
  ASSERT_EQ(b.size(), 2u);
  expect_point(b[0].end, 10, -5.5, 0);
  EXPECT_EQ(b[0].location.n_number, 10);
  expect_point(b[1].end, 10.5, -5.5, -1);
}

TEST(GcodeSinumerik, ComparisonsHaveTheLowestPriorityAsOnTheControl) {
  const auto b = read(
      "R1=1 R2=2\n"
      "G1 F100 X=(R1==1) AND (R2==2)\n"  // parenthesised: 1
      "Y=R1<>R2\n"
      "Z=NOT (R1>R2) + 0\n"
      "X=(R1 == 1 AND R2 == 2)\n"  // 1 == (1 AND R2) == 2: (1 == 1) == 2: 0
      "M30\n");
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[0].end.x(), 1.0);
  EXPECT_EQ(b[1].end.y(), 1.0);
  EXPECT_EQ(b[2].end.z(), 1.0);
  EXPECT_EQ(b[3].end.x(), 0.0);
}

TEST(GcodeSinumerik, LabelsGotofGotobAndBlockNumbers) {
  const auto b = read(
      "N10 R1=30 R2=10 R4=3\n"
      "N20 GOTOF MIDDLE\n"
      "N30 G1 F100 X=999\n"
      "N40 REPEAT_HERE: G1 F100 X=R1\n"
      "N50 R1=R1+R2 R4=R4-1\n"
      "N60 IF R4>0 GOTOB REPEAT_HERE\n"
      "N70 GOTOF 90\n"
      "N80 X=999\n"
      "N90 GOTOC NOWHERE\n"
      "N100 GOTO FINISH\n"
      "N110 X=999\n"
      "N120 FINISH: M30\n"
      "MIDDLE: G0 Y=1\n"
      "GOTOB REPEAT_HERE\n");
  // MIDDLE: Y1, then X30, X40, X50
  ASSERT_EQ(b.size(), 4u);
  expect_point(b[0].end, 0, 1, 0);
  EXPECT_EQ(b[1].end.x(), 30.0);
  EXPECT_EQ(b[2].end.x(), 40.0);
  EXPECT_EQ(b[3].end.x(), 50.0);
  EXPECT_EQ(b[3].location.line, 4);
  EXPECT_EQ(error_of("GOTOF NIRGENDS\nM30\n"), "s.mpf:1:1: GOTOF NIRGENDS: jump target not found after this line (dialect sinumerik)");
  EXPECT_EQ(error_of("G0 X1\nGOTOB N5\nM30\n"), "s.mpf:2:1: GOTOB N5: jump target not found before this line (dialect sinumerik)");
}

TEST(GcodeSinumerik, IfElseWhileForRepeat) {
  const auto b = read(
      "DEF INT I\n"
      "DEF REAL Y_CUR=0\n"
      "R1=5\n"
      "IF R1>3\n"
      "  G1 F100 X1\n"
      "ELSE\n"
      "  G1 F100 X2\n"
      "ENDIF\n"
      "IF R1<3\n"
      "  X3\n"
      "ELSE\n"
      "  X4\n"
      "ENDIF\n"
      "FOR I=1 TO 3\n"
      "  Y=I*10\n"
      "ENDFOR\n"
      "WHILE Y_CUR<2\n"
      "  Y_CUR=Y_CUR+1\n"
      "  Z=-Y_CUR\n"
      "ENDWHILE\n"
      "REPEAT\n"
      "  R1=R1-2\n"
      "  X=R1\n"
      "UNTIL R1<0\n"
      "M30\n");
  std::vector<double> xs, ys, zs;
  ASSERT_EQ(b.size(), 10u);
  expect_point(b[0].end, 1, 0, 0);
  expect_point(b[1].end, 4, 0, 0);
  expect_point(b[2].end, 4, 10, 0);
  expect_point(b[3].end, 4, 20, 0);
  expect_point(b[4].end, 4, 30, 0);
  expect_point(b[5].end, 4, 30, -1);
  expect_point(b[6].end, 4, 30, -2);
  expect_point(b[7].end, 3, 30, -2);
  expect_point(b[8].end, 1, 30, -2);
  expect_point(b[9].end, -1, 30, -2);
}

TEST(GcodeSinumerik, NestedLoopsAndAFalseWhileSkipItsBody) {
  const auto b = read(
      "DEF INT I, J\n"
      "G1 F100\n"
      "FOR I=1 TO 2\n"
      "  FOR J=1 TO 2\n"
      "    X=I Y=J\n"
      "  ENDFOR\n"
      "ENDFOR\n"
      "WHILE FALSE\n"
      "  WHILE TRUE\n"
      "  ENDWHILE\n"
      "  X=99\n"
      "ENDWHILE\n"
      "M30\n");
  ASSERT_EQ(b.size(), 4u);
  expect_point(b[3].end, 2, 2, 0);
}

TEST(GcodeSinumerik, RepeatedProgramSections) {
  const auto b = read("R1=0\nSTART: R1=R1+1\nG1 F100 X=R1\nREPEAT START P=2\nY1\nM30\n");
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[2].end.x(), 3.0);
  expect_point(b[3].end, 3, 1, 0);
  const auto c = read(
      "G1 F100\nA1: X1\nA2: X2\nA3: X3\nREPEAT A1 A2\nREPEATB A3 P=2\nB1: Y1\nY2\nENDLABEL: Y3\nZ1\n"
      "REPEAT B1 P=1\nM30\n");
  std::vector<double> v;
  for (const auto& blk : c) v.push_back(blk.end.x() * 100 + blk.end.y() * 10 + blk.end.z());
  const std::vector<double> expected = {100, 200, 300, 100, 200, 300, 300, 310, 320, 330, 331, 311, 321, 331};
  EXPECT_EQ(v, expected);
}

TEST(GcodeSinumerik, AnEndlessLoopIsStoppedByTheLoopLimit) {
  ReaderOptions o = sinumerik();
  o.max_loop_iterations = 50;
  EXPECT_EQ(error_of("G1 F100 X1\nLOOP\n  X=2\nENDLOOP\nM30\n", o),
            "s.mpf:4:1: LOOP: more than 50 loop iterations, jumps back and calls in the program (endless loop?) (dialect sinumerik)");
  EXPECT_EQ(error_of("L1: G1 F100 X1\nGOTOB L1\nM30\n", o),
            "s.mpf:2:1: L1: more than 50 loop iterations, jumps back and calls in the program (endless loop?) (dialect sinumerik)");
}

TEST(GcodeSinumerik, CrArcsHaveTheirCentreAndDirection) {
  // from (0,0) to (20,0): CR=10 is a half circle; CR=-15 the larger arc
  const auto b = read("G17 G90 G1 F100 X0 Y0\nG2 X20 Y0 CR=10\nG3 X0 Y0 CR=15\nG2 X20 CR=-15\nM30\n");
  ASSERT_EQ(b.size(), 4u);
  ASSERT_EQ(b[1].type, BlockType::arc);
  const auto& a1 = std::get<HelixArc>(b[1].geometry);
  expect_point(a1.frame().centre, 10, 0, 0);
  EXPECT_LT(a1.frame().normal.z(), 0.0);  // clockwise
  const auto& a2 = std::get<HelixArc>(b[2].geometry);
  EXPECT_GT(a2.frame().normal.z(), 0.0);
  EXPECT_NEAR(a2.frame().centre.x(), 10.0, 1e-9);
  EXPECT_LT(a2.sweep_rad(), std::numbers::pi);  // CR > 0: at most a half circle
  const auto& a3 = std::get<HelixArc>(b[3].geometry);
  EXPECT_GT(a3.sweep_rad(), std::numbers::pi);  // CR < 0: more than a half circle
  EXPECT_NEAR(std::abs(a3.frame().centre.y()), std::sqrt(15.0 * 15.0 - 100.0), 1e-9);
  // a full circle with its centre absolute (I=AC), a helix with TURN=
  const auto c = read("G1 F100 X0 Y10\nG3 I=AC(0) J=AC(0)\nG2 X0 Y10 Z-2 I0 J-10 TURN=2\nM30\n");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_NEAR(std::get<HelixArc>(c[1].geometry).sweep_rad(), 2 * std::numbers::pi, 1e-12);
  expect_point(std::get<HelixArc>(c[1].geometry).frame().centre, 0, 0, 0);
  EXPECT_NEAR(std::get<HelixArc>(c[2].geometry).sweep_rad(), 6 * std::numbers::pi, 1e-12);
}

TEST(GcodeSinumerik, CipCirclesMessagesAndStopre) {
  const auto b = read("G1 F100 X0 Y0\nMSG(\"ROUGH \" << 1)\nSTOPRE\nCIP X20 Y0 I1=10 J1=10\nMSG(\"\")\nM30\n");
  ASSERT_EQ(b.size(), 2u);
  ASSERT_EQ(b[1].type, BlockType::circle_3d);
  expect_point(b[1].via[0], 10, 10, 0);
  expect_point(b[1].end, 20, 0, 0);
  const auto w = warnings_of("MSG(\"A\")\nMSG(\"B\")\nM30\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "s.mpf:1:1: warning: MSG(..): messages are not shown by Kontur (warned once)");
}

TEST(GcodeSinumerik, ArcsByTheirOpeningAngle) {
  // end point and angle: 90 degrees over a chord of 10 * sqrt(2): radius 10
  const auto b = read("G17 G90 G1 F100 X0 Y0\nG3 X10 Y10 AR=90\nG2 X20 Y0 AR=270\nG3 I0 J-10 AR=180\nM30\n");
  ASSERT_EQ(b.size(), 4u);
  const auto& a1 = std::get<HelixArc>(b[1].geometry);
  expect_point(a1.frame().centre, 0, 10, 0);  // counter-clockwise from (0, 0) to (10, 10)
  EXPECT_NEAR(a1.sweep_rad(), std::numbers::pi / 2, 1e-12);
  const auto& a2 = std::get<HelixArc>(b[2].geometry);
  EXPECT_NEAR(a2.sweep_rad(), 1.5 * std::numbers::pi, 1e-9);
  // centre and angle: from (20, 0) about (20, -10), half a circle counter-clockwise to (20, -20)
  expect_point(b[3].end, 20, -20, 0);
  expect_point(std::get<HelixArc>(b[3].geometry).frame().centre, 20, -10, 0);
}

TEST(GcodeSinumerik, AcAndIcOverrideTheDistanceModeOfOneWord) {
  const auto b = read("G90 G1 F100 X10 Y10\nX=IC(5) Y20\nG91 X=AC(1) Y5\nX2\nM30\n");
  ASSERT_EQ(b.size(), 4u);
  expect_point(b[1].end, 15, 20, 0);
  expect_point(b[2].end, 1, 25, 0);
  expect_point(b[3].end, 3, 25, 0);
}

TEST(GcodeSinumerik, TransAndRotGiveExactMachineCoordinates) {
  const auto b = read(
      "G90 G17 G0 X0 Y0 Z0\n"
      "TRANS X100 Y50\n"
      "G1 F100 X10 Y0\n"
      "AROT RPL=90\n"
      "X10 Y0\n"
      "ATRANS X5\n"
      "X0 Y0\n"
      "ROT Z=90\n"  // replaces the whole frame: rotation only
      "X10 Y0\n"
      "TRANS\n"
      "X1 Y2\n"
      "MIRROR X0\n"
      "X3 Y4\n"
      "M30\n");
  ASSERT_EQ(b.size(), 7u);
  expect_point(b[1].end, 110, 50, 0);
  expect_point(b[2].end, 100, 60, 0);
  expect_point(b[3].end, 100, 55, 0);  // ATRANS in the rotated frame: X5 is machine +Y 5
  expect_point(b[4].end, 0, 10, 0);
  expect_point(b[5].end, 1, 2, 0);
  expect_point(b[6].end, -3, 4, 0);
}

TEST(GcodeSinumerik, ScaleMakesArcsLargerAndRefusesUnevenPlanes) {
  const auto b = read(
      "G17 G90 G0 X0 Y0\n"
      "SCALE X2 Y2\n"
      "ATRANS X5\n"  // scaled: 10 in the machine
      "G1 F100 X10 Y0\n"
      "G2 X20 Y0 CR=5\n"
      "SCALE\n"
      "G1 X1 Y1\n"
      "M30\n");
  ASSERT_EQ(b.size(), 4u);
  expect_point(b[1].end, 30, 0, 0);
  ASSERT_EQ(b[2].type, BlockType::arc);
  expect_point(b[2].end, 50, 0, 0);
  expect_point(std::get<HelixArc>(b[2].geometry).frame().centre, 40, 0, 0);
  EXPECT_NEAR(std::get<HelixArc>(b[2].geometry).radius_mm(), 10.0, 1e-12);
  expect_point(b[3].end, 1, 1, 0);
  EXPECT_EQ(
      error_of("G1 F100 X10\nSCALE X2 Y3\nG2 X20 CR=10\nM30\n"),
      "s.mpf:3:1: G2: the programmable frame scales the arc's plane unevenly: the arc would not be a circle in the "
      "machine (dialect sinumerik)");
}

TEST(GcodeSinumerik, AMirroredArcTurnsTheOtherWay) {
  const auto b = read("G0 X10 Y0\nMIRROR X0\nG0 X10 Y0\nG3 F100 X0 Y10 CR=10\nM30\n");
  ASSERT_EQ(b.size(), 3u);
  expect_point(b[1].end, -10, 0, 0);
  const auto& a = std::get<HelixArc>(b[2].geometry);
  expect_point(b[2].end, 0, 10, 0);
  expect_point(a.frame().centre, 0, 0, 0);
  EXPECT_LT(a.frame().normal.z(), 0.0);  // G3 mirrored in X: clockwise in the machine
}

TEST(GcodeSinumerik, PolarCoordinatesAboutThePole) {
  const auto b = read(
      "G17 G90\nG111 X10 Y10\n"
      "G1 F100 AP=90 RP=5\n"
      "AP=180\n"     // RP stays 5 (the position's)
      "G3 AP=270\n"  // an arc about the pole
      "G110 X5\n"    // the pole 5 to the right of the position (10, 5)
      "G1 RP=1 AP=0 Z-1\n"
      "M30\n");
  ASSERT_EQ(b.size(), 4u);
  expect_point(b[0].end, 10, 15, 0);
  expect_point(b[1].end, 5, 10, 0);
  ASSERT_EQ(b[2].type, BlockType::arc);
  expect_point(b[2].end, 10, 5, 0);
  expect_point(std::get<HelixArc>(b[2].geometry).frame().centre, 10, 10, 0);
  EXPECT_NEAR(std::get<HelixArc>(b[2].geometry).sweep_rad(), std::numbers::pi / 2, 1e-12);
  expect_point(b[3].end, 16, 5, -1);
}

TEST(GcodeSinumerik, CtArcsAreTangentToThePreviousMove) {
  const auto b = read("G17 G1 F100 X0 Y0\nX10\nCT X20 Y10\nX30 Y20\nM30\n");
  ASSERT_EQ(b.size(), 4u);
  const auto& a1 = std::get<HelixArc>(b[2].geometry);
  expect_point(a1.frame().centre, 10, 10, 0);
  EXPECT_GT(a1.frame().normal.z(), 0.0);               // counter-clockwise, leaving along +X
  const auto& a2 = std::get<HelixArc>(b[3].geometry);  // CT is modal
  expect_point(a2.frame().centre, 30, 10, 0);
  EXPECT_LT(a2.frame().normal.z(), 0.0);
  EXPECT_EQ(error_of("CT X5 Y5\nM30\n"),
            "s.mpf:1:1: CT: no direction to be tangent to (a tangential arc needs a move before it that is not along "
            "the plane's normal) (dialect sinumerik)");
}

TEST(GcodeSinumerik, Cycle81And82ExpandIntoTheirMoves) {
  const auto b = read("G17 G90 G0 X10 Y20 Z50 F200\nCYCLE82(40,0,2,-15,,1.5)\nG1 X11\nM30\n");
  ASSERT_EQ(b.size(), 6u);
  EXPECT_EQ(b[1].type, BlockType::rapid);
  expect_point(b[1].end, 10, 20, 2);
  EXPECT_EQ(b[2].type, BlockType::line);
  expect_point(b[2].end, 10, 20, -15);
  EXPECT_EQ(b[3].type, BlockType::dwell);
  EXPECT_EQ(b[3].dwell_s, 1.5);
  EXPECT_EQ(b[4].type, BlockType::rapid);
  expect_point(b[4].end, 10, 20, 40);
  EXPECT_EQ(b[5].type, BlockType::line);  // the G1 of the caller
  // DPR (relative depth) wins over DP, as on the control; MCALL calls it after each position
  const auto m = read("G90 G0 X0 Y0 Z10 F100\nMCALL CYCLE81(10,0,1,-50,5)\nG0 X1\nY2\nMCALL\nX3\nM30\n");
  ASSERT_EQ(m.size(), 1u + 4u + 4u + 1u);
  expect_point(m[1].end, 1, 0, 10);
  expect_point(m[2].end, 1, 0, 1);
  expect_point(m[3].end, 1, 0, -5);
  expect_point(m[4].end, 1, 0, 10);
  expect_point(m[8].end, 1, 2, 10);
  expect_point(m[9].end, 3, 2, 10);
}

TEST(GcodeSinumerik, Cycle83DrillsInStepsWithChipRemoval) {
  // RTP 10, RFP 0, SDIS 1, DP -12, FDEP -5, DAM 2, VARI 1: steps 5, 3, 2, 2 -> -5, -8, -10, -12
  const auto b = read("G90 G0 X0 Y0 Z10 F100\nCYCLE83(10,0,1,-12,,-5,,2,0,0,1,1)\nM30\n");
  std::vector<double> z;
  for (std::size_t i = 1; i < b.size(); ++i) z.push_back(b[i].end.z());
  const std::vector<double> expected = {1, -5, 1, -4.4, -8, 1, -7.4, -10, 1, -9.4, -12, 10};
  ASSERT_EQ(z.size(), expected.size());
  for (std::size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(z[i], expected[i], 1e-12) << i;
  // VARI 0: chip breaking, 1 mm back after each step
  const auto c = read("G90 G0 X0 Y0 Z10 F100\nCYCLE83(10,0,1,-9,,-5,,0,0,0,1,0)\nM30\n");
  std::vector<double> zc;
  for (std::size_t i = 1; i < c.size(); ++i) zc.push_back(c[i].end.z());
  const std::vector<double> expected_c = {1, -5, -4, -9, 10};
  ASSERT_EQ(zc.size(), expected_c.size());
  for (std::size_t i = 0; i < zc.size(); ++i) EXPECT_NEAR(zc[i], expected_c[i], 1e-12) << i;
}

TEST(GcodeSinumerik, SubprogramsOfTheSameFileWithParametersAndRepetitions) {
  const auto b = read(
      "%_N_MAIN_MPF\n"
      "G1 F100 X0\n"
      "STEP(5)\n"
      "STEP(1) P2\n"
      "HOLE\n"
      "M30\n"
      "%_N_STEP_SPF\n"
      "PROC STEP(REAL D)\n"
      "G91 X=D\n"
      "G90\n"
      "RET\n"
      "%_N_HOLE_SPF\n"
      "G1 Y7\n"
      "M17\n");
  ASSERT_EQ(b.size(), 5u);
  EXPECT_EQ(b[1].end.x(), 5.0);
  EXPECT_EQ(b[2].end.x(), 6.0);
  EXPECT_EQ(b[3].end.x(), 7.0);
  expect_point(b[4].end, 7, 7, 0);
  EXPECT_EQ(error_of("G0 X0\nWARMUP_CYCLE(3600, 600)\nM30\n"),
            "s.mpf:2:1: WARMUP_CYCLE: unknown word, or a subprogram found neither in this file nor as WARMUP_CYCLE.SPF "
            "beside it (dialect sinumerik)");
}

TEST(GcodeSinumerik, ASubprogramOfItsOwnFileBesideTheProgramIsCalled) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "kontur_sinumerik_external";
  std::filesystem::create_directories(dir);
  {
    std::ofstream spf(dir / "WARM.SPF");
    spf << "%_N_WARM_SPF\n; a warm-up\nPROC WARM(REAL DEPTH, INT TIMES)\nDEF INT I\nFOR I=1 TO TIMES\n"
           "G1 SUPA Z=-DEPTH*I F300\nENDFOR\nRET\n";
    std::ofstream mpf(dir / "MAIN.MPF");
    mpf << "EXTERN WARM(REAL, INT)\nG71 G90 G0 X1 Y2 Z0\nWARM(2, 3)\nWARM(1, 1)\nG0 X5\nLAST\nG0 Y0\nM30\n";
    std::ofstream last(dir / "LAST.SPF");
    last << "G1 Y7 M17\n";
  }
  Reader reader((dir / "MAIN.MPF").string(), sinumerik());
  std::vector<Block> b;
  Block blk;
  while (reader.next(blk)) b.push_back(blk);
  ASSERT_EQ(b.size(), 1u + 3u + 1u + 1u + 2u);
  EXPECT_EQ(b[3].end.z(), -6.0);
  EXPECT_EQ(*b[3].location.file, (dir / "WARM.SPF").string());
  EXPECT_EQ(b[3].location.line, 6);
  EXPECT_EQ(b[4].end.z(), -1.0);
  expect_point(b[5].end, 5, 2, -1);
  EXPECT_EQ(*b[5].location.file, (dir / "MAIN.MPF").string());
  EXPECT_EQ(b[5].location.line, 5);
  EXPECT_EQ(*b[6].location.file, (dir / "LAST.SPF").string());  // the block with M17 is the subprogram's
  EXPECT_EQ(b[6].location.line, 1);
  EXPECT_EQ(*b[7].location.file, (dir / "MAIN.MPF").string());
  EXPECT_EQ(b[7].location.line, 7);
  expect_point(b[7].end, 5, 0, -1);
}

TEST(GcodeSinumerik, DwellsPathModesAndNoOps) {
  const auto b = read("S1200 M3\nG1 F100 X1\nG4 F2.5\nG4 S3\nG64 ADIS=0.05 X2\nG9 X3\nX4\nG60 X5\nSOFT\nBRISK\nM30\n");
  ASSERT_EQ(b.size(), 7u);
  EXPECT_EQ(b[1].dwell_s, 2.5);
  EXPECT_NEAR(b[2].dwell_s, 3 * 60.0 / 1200.0, 1e-12);
  EXPECT_EQ(b[3].modal.path_control, PathControl::blend);
  EXPECT_EQ(b[3].modal.blend_tolerance_mm, 0.05);
  EXPECT_EQ(b[4].modal.path_control, PathControl::exact_stop);  // G9: this block only
  EXPECT_EQ(b[5].modal.path_control, PathControl::blend);
  EXPECT_EQ(b[5].modal.blend_tolerance_mm, 0.05);
  EXPECT_EQ(b[6].modal.path_control, PathControl::exact_stop);
  const auto w = warnings_of("SOFT\nSOFT\nG1 F100 X1\nM30\n");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0], "s.mpf:1:1: warning: SOFT: accepted, no effect on Kontur's path (dialect sinumerik) (warned once)");
  // G70 / G700: inch
  const auto i = read("G700 G1 F10 X1\nM30\n");
  EXPECT_NEAR(i[0].end.x(), 25.4, 1e-12);
}

TEST(GcodeSinumerik, RefusalsNameTheLineTheFeatureAndTheDialect) {
  EXPECT_EQ(error_of("G0 X0\nCYCLE800(4,\"TC1\",200000,57,0,0,0,0,0,0,0,0,0,1,,1)\nM30\n"),
            "s.mpf:2:1: CYCLE800: 5-axis swivelling (CYCLE800: a swivel head or table) is not supported by Kontur "
            "(dialect sinumerik)");
  EXPECT_EQ(error_of("N10 TRAORI\nM30\n"),
            "s.mpf:1:5: TRAORI: the 5-axis transformation TRAORI is not supported by Kontur (dialect sinumerik)");
  EXPECT_EQ(error_of("G0 X0\nDIAMON\nM30\n"),
            "s.mpf:2:1: DIAMON: lathe diameter programming DIAMON is not supported by Kontur (dialect sinumerik)");
  EXPECT_EQ(error_of("G33 Z-10 K1.5\nM30\n"),
            "s.mpf:1:1: G33: thread cutting and tapping (spindle-synchronised motion) is not supported by Kontur "
            "(dialect sinumerik)");
  EXPECT_EQ(error_of("CYCLE95(\"KONTUR\",2,0,0,0,0,0,0,9)\nM30\n"),
            "s.mpf:1:1: CYCLE95: the lathe cycles CYCLE9x (turning, threading, grooving) is not supported by Kontur "
            "(dialect sinumerik)");
  EXPECT_EQ(error_of("G0 X0\nPOCKET4(10,0,2,15,40,50,51.75,2)\nM30\n"),
            "s.mpf:2:1: POCKET4: this machining cycle of the cycle package (only CYCLE81, CYCLE82 and CYCLE83 are "
            "expanded) is not supported by Kontur (dialect sinumerik)");
  EXPECT_EQ(error_of("G0 X0 FOO\nM30\n"), "s.mpf:1:7: FOO: unknown word or keyword (dialect sinumerik)");
  EXPECT_EQ(
      error_of("G0 X0 (COMMENT)\nM30\n"),
      "s.mpf:1:7: '(': unexpected; it is not a comment on a Sinumerik (comments start with ';'; dialect sinumerik)");
  EXPECT_EQ(error_of("G1 X=UNDEF\nM30\n"), "s.mpf:1:6: UNDEF: variable not defined (DEF it first) (dialect sinumerik)");
  EXPECT_EQ(error_of("IF R1==1\nG0 X1\nM30\n"), "s.mpf:1:1: IF: ENDIF not found before the end of the program (dialect sinumerik)");
  EXPECT_EQ(error_of("WHILE TRUE\nG0 X1\n"), "s.mpf:1:1: WHILE: the program ends inside it (ENDWHILE missing) (dialect sinumerik)");
}

TEST(GcodeSinumerik, ARealisticProgramWithItsHeader) {
  const std::string program =
      "%_N_PART_MPF\n"
      ";$PATH=/_N_WKS_DIR/_N_PART_WPD\n"
      "; a plate with four holes and a pocket outline\n"
      "DEF REAL SAFE=50, DEPTH=-3\n"
      "DEF INT I\n"
      "N10 G17 G90 G71 G54 G64 SOFT\n"
      "N20 T1 D1 M6\n"
      "N30 S3000 M3\n"
      "N40 G0 X0 Y0 Z=SAFE F200\n"
      "N50 MCALL CYCLE81(SAFE,0,2,-10)\n"
      "N60 FOR I=0 TO 3\n"
      "N70   G0 X=20*COS(90*I) Y=20*SIN(90*I)\n"
      "N80 ENDFOR\n"
      "N90 MCALL\n"
      "N100 G0 X-10 Y-10 Z2\n"
      "N110 G1 Z=DEPTH F300\n"
      "N120 X10\n"
      "N130 G3 X10 Y10 CR=10\n"  // chord 20 with radius 10: a half circle around (10, 0)... of (10,-10)-(10,10)
      "N140 G1 X-10\n"
      "N150 Y-10\n"
      "N160 G0 Z=SAFE\n"
      "N170 M30\n";
  Reader reader("PART.MPF", program, ReaderOptions{});
  EXPECT_EQ(reader.dialect().dialect, Dialect::sinumerik);
  std::vector<Block> b;
  Block blk;
  while (reader.next(blk)) b.push_back(blk);
  ASSERT_EQ(b.size(), 1u + 4u * 4u + 7u);
  expect_point(b[1 + 4 * 1].end, 0, 20, 50);  // the second hole's position
  expect_point(b[1 + 4 * 1 + 2].end, 0, 20, -10);
  const Block& arc = b[1 + 16 + 3];
  ASSERT_EQ(arc.type, BlockType::arc);
  expect_point(std::get<HelixArc>(arc.geometry).frame().centre, 10, 0, -3);
  expect_point(b.back().end, -10, -10, 50);
}

}  // namespace
}  // namespace kontur::gcode
