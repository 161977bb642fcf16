// Dialects: the name table, the detection of a program's dialect from its text (each kind of mark,
// their order of strength, the default), and the few rules in which a control differs from
// LinuxCNC's (Fanuc's G80 keeping the motion mode, grbl's `$` lines).
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

std::vector<Block> read(const std::string& program, ReaderOptions options = {}, const std::string& name = "t.nc") {
  Reader reader(name, program, options);
  std::vector<Block> blocks;
  Block b;
  while (reader.next(b)) blocks.push_back(b);
  return blocks;
}

std::string error_of(const std::string& program, ReaderOptions options) {
  try {
    read(program, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(GcodeDialect, NamesRoundTripAndUnknownNamesAreRefused) {
  for (Dialect d : all_dialects) EXPECT_EQ(parse_dialect(to_string(d)), d);
  EXPECT_EQ(parse_dialect("HAAS"), Dialect::haas);
  EXPECT_FALSE(parse_dialect("heidenhain").has_value());
  EXPECT_FALSE(parse_dialect("").has_value());
  EXPECT_EQ(dialect_names(), "linuxcnc|fanuc|haas|mitsubishi|sinumerik|grbl|mach3");
}

struct DetectionCase {
  const char* name;
  const char* file;
  const char* text;
  Dialect dialect;
  const char* reason;
};

class DialectDetection : public ::testing::TestWithParam<DetectionCase> {};

TEST_P(DialectDetection, TellsTheDialectAndTheMarkThatToldIt) {
  const DetectionCase& c = GetParam();
  const DialectChoice got = detect_dialect(c.file, c.text);
  EXPECT_EQ(got.dialect, c.dialect) << got.reason;
  EXPECT_EQ(got.reason, c.reason);
}

INSTANTIATE_TEST_SUITE_P(
    Gcode, DialectDetection,
    ::testing::Values(
        DetectionCase{"haas_program_number", "p.nc", "%\nO78237 (PART)\n(HAAS VF-2)\nG0 X0\nM30\n%\n", Dialect::haas,
                      "program number O78237 on line 2, and a comment naming HAAS on line 3"},
        DetectionCase{"fanuc_colon_number", "p.nc", ":0097\nG0 X0\nM30\n", Dialect::fanuc,
                      "program number :0097 on line 1"},
        DetectionCase{"fanuc_macro_while", "p.nc", "#1=0\nWHILE [#1 LT 3] DO1\n#1=#1+1\nEND1\nM30\n", Dialect::fanuc,
                      "'WHILE [#1 LT 3] DO1' on line 2"},
        DetectionCase{"fanuc_axis_words_after_g80", "p.nc", "G0 X0 Y0\nG81 X1 Z-1 R1 F50\nG80\nX5 Y5\nM30\n",
                      Dialect::fanuc, "axis words without a motion code after G80 on line 4 (a Fanuc keeps G0 / G1)"},
        DetectionCase{"g80_then_motion_code_is_no_mark", "p.nc", "G81 X1 Z-1 R1 F50\nG80\nG0 X5 Y5\nM2\n",
                      Dialect::linuxcnc, "no mark of another dialect in the first 4 lines: LinuxCNC's reading"},
        DetectionCase{"g80_then_nurbs_point_lines_is_no_mark", "p.ngc",
                      "G80\nF100\nG5.2 P1 L3\nX1 Y1 P1\nX2 Y0 P1\nG5.3\nG6.2 P2 K0 X2 Y0 Z0\nK0 X3 Y1 Z0\nK1\nK1\nM2\n",
                      Dialect::linuxcnc, "file extension .ngc"},
        DetectionCase{"mach3_units_code", "p.nc", "G00G21G17G90\nG71G91.1\nG0 X0\nM30\n", Dialect::mach3,
                      "Mach3's G71 on line 2"},
        DetectionCase{"mach3_safety_line_g50", "p.nc", "G0 G49 G40 G17 G80 G50 G90\nG0 X0\nM30\n", Dialect::mach3,
                      "Mach3's G50 on line 1"},
        DetectionCase{"lathe_g50_is_no_mach3_mark", "p.nc", "G50 S2000\nG0 X0\nM30\n", Dialect::linuxcnc,
                      "no mark of another dialect in the first 3 lines: LinuxCNC's reading"},
        DetectionCase{"haas_local_subprogram_call", "p.nc", "O1000\nG0 X0\nM97 P100\nM30\nN100 G0 X1\nM99\n",
                      Dialect::haas, "program number O1000 on line 1, and Haas's M97 on line 3"},
        DetectionCase{"fanuc_subprogram_call", "p.nc", "G0 X0\nM98 P1000 L2\nM30\n", Dialect::fanuc,
                      "'M98 P' on line 2"},
        DetectionCase{"mitsubishi_named", "p.nc", "O1000\n(MITSUBISHI M80)\nG0 X0\nM30\n", Dialect::mitsubishi,
                      "program number O1000 on line 1, and a comment naming MITSUBISHI on line 2"},
        DetectionCase{"sinumerik_header", "p.txt", "%_N_PART1_MPF\n;$PATH=/_N_WKS_DIR\nG0 X0\nM30\n",
                      Dialect::sinumerik, "Sinumerik's '%_N_PART1_MPF' on line 1"},
        DetectionCase{"sinumerik_r_parameter", "p.txt", "G0 X0\nR1=36 R2=5\nG1 X=R1\nM30\n", Dialect::sinumerik,
                      "Sinumerik's 'R1=' on line 2"},
        DetectionCase{"sinumerik_over_program_number", "p.txt", "O1\nDEF REAL DEPTH\nM30\n", Dialect::sinumerik,
                      "Sinumerik's 'DEF REAL' on line 2"},
        DetectionCase{"linuxcnc_o_word", "p.nc", "o<square> sub\nG1 X1\no<square> endsub\nM2\n", Dialect::linuxcnc,
                      "LinuxCNC's 'O<SQUARE> SUB' on line 1"},
        DetectionCase{"linuxcnc_named_parameter", "p.nc", "#<depth> = 2\nG1 Z-#<depth>\nM2\n", Dialect::linuxcnc,
                      "LinuxCNC's '#<' on line 1"},
        DetectionCase{"grbl_setting_line", "p.gcode", "$H\nG0 X0\n", Dialect::grbl, "grbl command '$H' on line 1"},
        DetectionCase{"mach3_named_in_comment", "p.tap", "(Post: Mach3 mill)\nG0 X0\nM30\n", Dialect::mach3,
                      "a comment naming MACH3 on line 1"},
        DetectionCase{"sinumerik_by_extension", "PART.MPF", "G0 X0\nM30\n", Dialect::sinumerik,
                      "file extension .mpf"},
        DetectionCase{"plain_program_is_linuxcnc", "p.nc", "G0 X0\nG1 X1 F100\nM2\n", Dialect::linuxcnc,
                      "no mark of another dialect in the first 3 lines: LinuxCNC's reading"},
        // Fanuc's `#1=` alone is also LinuxCNC's: not a mark.
        DetectionCase{"numbered_parameter_is_no_mark", "p.nc", "#1=2\nG1 X#1 F100\nM2\n", Dialect::linuxcnc,
                      "no mark of another dialect in the first 3 lines: LinuxCNC's reading"},
        // "O1234 G0" is not a program number line.
        DetectionCase{"o_word_with_code_is_no_program_number", "p.nc", "G0 X0\nM2\n(O1234)\n", Dialect::linuxcnc,
                      "no mark of another dialect in the first 3 lines: LinuxCNC's reading"}),
    [](const ::testing::TestParamInfo<DetectionCase>& i) { return std::string(i.param.name); });

TEST(GcodeDialect, ReaderDetectsTheDialectUnlessOneIsGiven) {
  Reader detected("p.nc", "O1234 (PART)\nG0 X1\nM30\n");
  EXPECT_EQ(detected.dialect().dialect, Dialect::fanuc);
  EXPECT_EQ(detected.dialect().reason, "program number O1234 on line 1");
  ReaderOptions options;
  options.dialect = Dialect::mach3;
  Reader given("p.nc", "O1234 (PART)\nG0 X1\nM30\n", options);
  EXPECT_EQ(given.dialect().dialect, Dialect::mach3);
  EXPECT_EQ(given.dialect().reason, "given");
}

// A Fanuc keeps G0 / G1 modal through a drilling cycle: after G80, axis words move in that mode.
TEST(GcodeDialect, FanucG80RestoresTheMotionModeBeforeTheCycle) {
  const std::string program = "G90 G17 G21\nG0 Z10\nG1 X0 Y0 F300\nG81 X10 Y0 Z-2 R2 F100\nG80\nX20 Y5\nM30\n";
  ReaderOptions fanuc;
  fanuc.dialect = Dialect::fanuc;
  const auto blocks = read(program, fanuc);
  ASSERT_FALSE(blocks.empty());
  const Block& last = blocks.back();
  EXPECT_EQ(last.type, BlockType::line);  // G1, as before the cycle
  EXPECT_DOUBLE_EQ(last.end.x(), 20.0);
  EXPECT_DOUBLE_EQ(last.end.y(), 5.0);
  EXPECT_DOUBLE_EQ(last.feed.value, 100.0);  // F is modal: the cycle's
  // LinuxCNC refuses the same program: G80 left no motion mode.
  ReaderOptions linuxcnc;
  linuxcnc.dialect = Dialect::linuxcnc;
  EXPECT_NE(error_of(program, linuxcnc).find("axis words without a motion command"), std::string::npos);
}

// Fanuc posts write "G00 G91 G28 Z0": G0 sets the mode, Z0 is G28's (incremental: home straight up).
TEST(GcodeDialect, FanucMotionCodeBesideG28OnlySetsTheMode) {
  const std::string program = "G21 G90\nG0 X5 Y5 Z5\nG00 G91 G28 Z0\nG90\nX7\nM30\n";
  ReaderOptions fanuc;
  fanuc.dialect = Dialect::fanuc;
  const auto blocks = read(program, fanuc);
  ASSERT_EQ(blocks.size(), 4u);  // G0; G28 through its intermediate point (here: where it is); X7
  EXPECT_EQ(blocks[2].type, BlockType::rapid);  // G28 to the reference position (#5161.. = 0) in Z only
  EXPECT_DOUBLE_EQ(blocks[2].end.z(), 0.0);
  EXPECT_DOUBLE_EQ(blocks[2].end.x(), 5.0);
  EXPECT_EQ(blocks[3].type, BlockType::rapid);  // G0 stayed the motion mode
  EXPECT_DOUBLE_EQ(blocks[3].end.x(), 7.0);
  ReaderOptions linuxcnc;
  linuxcnc.dialect = Dialect::linuxcnc;
  EXPECT_EQ(error_of(program, linuxcnc), "t.nc:3:9: G28 and G0 in one block: both use the axis words (dialect linuxcnc)");
}

// An M98 ignored as a machine's own M code would run the subprogram's body once instead of L times.
TEST(GcodeDialect, SubprogramCallsAreNeverIgnoredInLinuxcnc) {
  ReaderOptions linuxcnc;
  linuxcnc.dialect = Dialect::linuxcnc;
  EXPECT_EQ(error_of("G0 X0\nM98 P200 L6\nM2\n", linuxcnc),
            "t.nc:2:1: M98: subprogram calls and returns (M97, M98, M99) are not LinuxCNC's: read the program with "
            "--dialect fanuc, haas or mach3 (dialect linuxcnc)");
}

// LinuxCNC's SUBROUTINE_PATH: o<name> call of a subroutine the program does not define runs
// name.ngc from the first folder that has it; blocks and messages name the file they come from.
TEST(GcodeDialect, LinuxcncSubroutineInItsOwnFileIsFoundOnThePath) {
  const auto dir = std::filesystem::temp_directory_path() / "kontur_subroutine_path_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "subs");
  std::ofstream(dir / "subs" / "square.ngc") << "(a square of side #1)\no<square> sub\nG91 G1 X#1 F100\nY#1\n"
                                                "X-#1\nY-#1\nG90\no<square> endsub\nM2\n";
  std::ofstream(dir / "subs" / "broken.ngc") << "o<broken> sub\nG1 Q\no<broken> endsub\n";
  std::ofstream(dir / "main.ngc") << "G21 G90\nG0 X1 Y1\no<square> call [2]\no<square> call [3]\nG0 X0\nM2\n";
  ReaderOptions options;
  options.dialect = Dialect::linuxcnc;
  options.subroutine_path = {(dir / "nothing_here").string(), (dir / "subs").string()};
  Reader reader((dir / "main.ngc").string(), options);
  std::vector<Block> blocks;
  Block b;
  while (reader.next(b)) blocks.push_back(b);
  ASSERT_EQ(blocks.size(), 10u);  // G0, 4 sides twice, G0
  EXPECT_DOUBLE_EQ(blocks[1].end.x(), 3.0);
  EXPECT_DOUBLE_EQ(blocks[5].end.x(), 4.0);  // the second call, side 3
  EXPECT_DOUBLE_EQ(blocks[8].end.y(), 1.0);
  EXPECT_EQ(blocks[1].location.line, 3);
  EXPECT_NE(blocks[1].location.file->find("square.ngc"), std::string::npos);
  EXPECT_NE(blocks[9].location.file->find("main.ngc"), std::string::npos);
  EXPECT_EQ(blocks[9].location.line, 5);

  // Not found: the message names the file looked for and the folders.
  options.subroutine_path = {(dir / "nothing_here").string()};
  try {
    Reader missing((dir / "main.ngc").string(), options);
    while (missing.next(b)) {
    }
    FAIL() << "o<square> call read without its file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":3:1: O<SQUARE> call: subroutine not defined in the program, and no "
                                         "square.ngc in the subroutine path"),
              std::string::npos)
        << e.what();
  }
  // An error inside the subroutine's file names that file and its line.
  std::ofstream(dir / "main2.ngc") << "G0 X0\no<broken> call\nM2\n";
  options.subroutine_path = {(dir / "subs").string()};
  try {
    Reader broken((dir / "main2.ngc").string(), options);
    while (broken.next(b)) {
    }
    FAIL() << "a broken subroutine read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.ngc:2:"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(GcodeDialect, LinuxcncPolarCoordinatesAboutTheOriginAndCumulativeInG91) {
  ReaderOptions linuxcnc;
  linuxcnc.dialect = Dialect::linuxcnc;
  const auto blocks = read("G21 G90 G17\nG1 @10 ^90 F100\n^180\n@5\nG91 @1 ^-90\nG90 G1 X0 Y0\nM2\n", linuxcnc);
  ASSERT_EQ(blocks.size(), 5u);
  EXPECT_NEAR(blocks[0].end.x(), 0.0, 1e-12);  // @10 ^90 is Y10
  EXPECT_DOUBLE_EQ(blocks[0].end.y(), 10.0);
  EXPECT_DOUBLE_EQ(blocks[1].end.x(), -10.0);  // ^180 keeps the radius 10
  EXPECT_NEAR(blocks[1].end.y(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(blocks[2].end.x(), -5.0);  // @5 keeps the angle 180
  EXPECT_NEAR(blocks[3].end.x(), 0.0, 1e-12);  // G91: radius 5 + 1, angle 180 - 90
  EXPECT_DOUBLE_EQ(blocks[3].end.y(), 6.0);
  EXPECT_EQ(error_of("G21 G91\nG1 @1 ^10 F100\n", linuxcnc),
            "t.nc:2:4: @ ^: an incremental polar move cannot start at the origin (no angle there) (dialect linuxcnc)");
  EXPECT_EQ(error_of("G21\nG1 X1 @1 F100\n", linuxcnc),
            "t.nc:2:4: X: an axis of the plane with @ ^ in one block (polar coordinates give both) (dialect linuxcnc)");
  EXPECT_EQ(error_of("G21 G18\nG1 @1 ^10 F100\n", linuxcnc),
            "t.nc:2:4: @ ^: LinuxCNC's polar coordinates are in the XY plane only (G17) (dialect linuxcnc)");
  ReaderOptions fanuc;
  fanuc.dialect = Dialect::fanuc;
  EXPECT_EQ(error_of("G1 @1 ^10 F100\n", fanuc),
            "t.nc:1:4: '@': LinuxCNC's polar coordinates (@ radius, ^ angle) are not words of dialect fanuc");
}

// LinuxCNC's INI CENTER_ARC_RADIUS_TOLERANCE_MM: radii 0.02 mm apart read by default (0.0283), refused at 0.001.
TEST(GcodeDialect, ArcRadiusToleranceFromTheMachine) {
  const std::string program = "G21 G90 G17\nG0 X0 Y0\nG2 X10.02 Y0 I5 J0 F100\nM2\n";
  ReaderOptions options;
  options.dialect = Dialect::linuxcnc;
  EXPECT_EQ(read(program, options).size(), 2u);
  options.arc_radius_tolerance_mm = 0.001;
  EXPECT_NE(error_of(program, options).find("t.nc:3:1: G2: radius to the start 5 mm and to the end"), std::string::npos)
      << error_of(program, options);
}

TEST(GcodeDialect, GrblSettingLinesAreIgnoredWithAWarningAndHomingOrJoggingIsRefused) {
  ReaderOptions grbl;
  grbl.dialect = Dialect::grbl;
  Reader reader("g.gcode", "$32=0\n$X\nG21 G90\nG1 X5 F100\nM2\n", grbl);
  Block b;
  int n = 0;
  while (reader.next(b)) ++n;
  EXPECT_EQ(n, 1);
  ASSERT_EQ(reader.warning_count(), 2u);
  EXPECT_NE(reader.warnings()[0].find("g.gcode:1:1: warning: $32=0: a grbl setting or command, ignored"),
            std::string::npos);
  EXPECT_EQ(error_of("G21\nG0 X1\n$H\nG1 X1 F100\n", grbl),
            "t.nc:3:1: $H: grbl's homing cycle in the middle of a program moves to the machine's home switches, which "
            "a machine file does not give (dialect grbl); home the machine before the program");
  Reader homed("h.gcode", "$X\nG21\n$H\nG90\nG1 X5 F100\nM2\n", grbl);  // homing first: where the run starts
  while (homed.next(b)) {
  }
  EXPECT_EQ(homed.warning_count(), 2u);
  EXPECT_NE(error_of("$J=G91 X10 F100\n", grbl).find("t.nc:1:1: $J=G91 X10 F100: a grbl jog is a manual motion"),
            std::string::npos);
  // In LinuxCNC a '$' line is not G-code.
  ReaderOptions linuxcnc;
  linuxcnc.dialect = Dialect::linuxcnc;
  EXPECT_NE(error_of("$X\n", linuxcnc), "");
}

}  // namespace
}  // namespace kontur::gcode
