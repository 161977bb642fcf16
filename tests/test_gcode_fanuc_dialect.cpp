// The Fanuc family's front end (fanuc, haas, mitsubishi, mach3): program numbers and
// subprograms (M98 / M99 / M97, G65 with arguments), Custom Macro B (variables, vacant #0,
// expressions, system variables), IF / GOTO / WHILE control flow, the Fanuc cycles G84-G89,
// the codes read as no-ops, and every refusal's message.
#include <gtest/gtest.h>

#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

struct Read {
  std::vector<Block> blocks;
  std::vector<std::string> warnings;
};

Read read(const std::string& program, Dialect d = Dialect::fanuc, ReaderOptions o = {}) {
  o.dialect = d;
  Reader reader("p.nc", program, o);
  Read out;
  Block b;
  while (reader.next(b)) out.blocks.push_back(b);
  out.warnings = reader.warnings();
  return out;
}

std::string error_of(const std::string& program, Dialect d = Dialect::fanuc, ReaderOptions o = {}) {
  try {
    read(program, d, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<Vec3> ends(const Read& r) {
  std::vector<Vec3> e;
  for (const Block& b : r.blocks)
    if (b.type != BlockType::dwell) e.push_back(b.end);
  return e;
}

bool has_warning(const Read& r, const std::string& part) {
  for (const auto& w : r.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

TEST(GcodeFanucDialect, MacroBWhileLoopGivesExactEndPoints) {
  const auto r = read(
      "%\nO1000 (LOOP)\nG21 G90 G17 F100.\n#1 = 0\nWHILE [#1 LT 4] DO1\nG1 X[#1 * 2.5] Y[#1 * #1]\n"
      "#1 = #1 + 1\nEND1\nM30\n%\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(e[static_cast<std::size_t>(i)].x(), i * 2.5);
    EXPECT_DOUBLE_EQ(e[static_cast<std::size_t>(i)].y(), i * i);
  }
  EXPECT_EQ(r.blocks[3].location.line, 6);  // every pass reports the loop's line
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
}

TEST(GcodeFanucDialect, NestedLoopsAndAFalseWhileSkipsToItsEnd) {
  const auto r = read(
      "G21 F100.\n#1=0\nWHILE[#1LT2]DO1\n#2=0\nWHILE[#2LT3]DO2\nG1X#1Y#2\n#2=#2+1\nEND2\n#1=#1+1\nEND1\n"
      "WHILE[#1GT100]DO1\nG1X99.\nEND1\nG1 Z-1.\nM30\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 7u);
  EXPECT_EQ(e[4], Vec3(1, 1, 0));
  EXPECT_EQ(e[6], Vec3(1, 2, -1));
}

TEST(GcodeFanucDialect, EndlessWhileIsStoppedByTheLoopLimit) {
  ReaderOptions o;
  o.max_loop_iterations = 50;
  EXPECT_EQ(error_of("G21 F100.\nWHILE [1 EQ 1] DO1\nG91 G1 X1.\nEND1\nM30\n", Dialect::fanuc, o),
            "p.nc:2:1: WHILE [..] DO1: more than 50 loop iterations, jumps back and calls in the program (endless "
            "loop?) (dialect fanuc)");
}

TEST(GcodeFanucDialect, ALoopWithoutItsEndIsRefused) {
  EXPECT_EQ(error_of("G21 F100.\nWHILE [1 EQ 1] DO1\nG1 X1.\n"),
            "p.nc:2:1: DO1: the program ends inside the loop (END1 missing) (dialect fanuc)");
  EXPECT_EQ(error_of("G21 F100.\nWHILE [1 EQ 2] DO2\nG1 X1.\n"),
            "p.nc:2:1: WHILE [..] DO2: END2 not found before the end of the program (dialect fanuc)");
  EXPECT_EQ(error_of("G21\nEND1\n"), "p.nc:2:1: END1: no open WHILE [..] DO1 (dialect fanuc)");
}

TEST(GcodeFanucDialect, IfGotoJumpsForwardAndBackward) {
  const auto r = read(
      "G21 G90 F100.\n#1=0\nN10 #1=#1+1\nG1 X#1\nIF [#1 LT 3] GOTO10\nGOTO 30\nG1 X99.\nN30 G1 Y5.\n"
      "IF [#1 EQ 3] THEN #2=7\nG1 Z-#2\nM30\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[2], Vec3(3, 0, 0));
  EXPECT_EQ(e[3], Vec3(3, 5, 0));
  EXPECT_EQ(e[4], Vec3(3, 5, -7));
  EXPECT_EQ(r.blocks[3].location.line, 8);
  EXPECT_EQ(error_of("GOTO 77\nM30\n"), "p.nc:1:1: GOTO 77: no block N77 in this program (dialect fanuc)");
}

TEST(GcodeFanucDialect, VacantVariablesOmitTheirWordsAndCompareApartFromZero) {
  const auto r = read(
      "G21 G90 F100.\nG1 X1. Y2.\n#5 = 0\nG1 X#1 Y#5\nIF [#1 EQ #0] THEN #6 = 1\nIF [#5 EQ #0] THEN #6 = 2\n"
      "IF [#1 EQ 0] THEN #7 = 1\n#8 = #1 + 4\nG1 Z-[#6 + #8]\n#9 = #0\nG1 X#9\nM30\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[1], Vec3(1, 0, 0));   // X#1 vacant: X omitted
  EXPECT_EQ(e[2], Vec3(1, 0, -5));  // #6 = 1 (vacant EQ #0, 0 NE #0), #8 = 0 + 4
  EXPECT_EQ(r.blocks.size(), 3u);   // G1 X#9 (vacant): no motion word, no block
}

TEST(GcodeFanucDialect, ExpressionsFollowFanucsPrecedenceAndFunctions) {
  const auto r = read(
      "G21 G90 F100.\n#1 = 2 + 3 * 4\n#2 = ATAN[-1]/[-1]\n#3 = FIX[-1.7] + FUP[1.2] + ROUND[2.5]\n"
      "#4 = SQRT[16] + ABS[-2] + POW[2,3] + [7 MOD 4] + BIN[BCD[12]]\n#5 = [1 OR 2] + [6 AND 3] + [5 XOR 1]\n"
      "G1 X#1 Y#2 Z#3\nG1 X#4 Y#5 Z[SIN[30] + COS[60]]\nM30\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_DOUBLE_EQ(e[0].x(), 14.0);
  EXPECT_DOUBLE_EQ(e[0].y(), 225.0);  // 0..360 degrees
  EXPECT_DOUBLE_EQ(e[0].z(), -1.0 + 2.0 + 3.0);
  EXPECT_DOUBLE_EQ(e[1].x(), 4.0 + 2.0 + 8.0 + 3.0 + 12.0);
  EXPECT_DOUBLE_EQ(e[1].y(), 3.0 + 2.0 + 4.0);
  EXPECT_NEAR(e[1].z(), 1.0, 1e-12);
  EXPECT_EQ(error_of("#1 = 1 / [2 - 2]\n"), "p.nc:1:8: '/[2-2]': division by zero (dialect fanuc)");
}

TEST(GcodeFanucDialect, M98RepeatsAndNestedCallsRunSubprogramsAfterTheMain) {
  const auto r = read(
      "%\nO0001 (MAIN)\nG21 G90 G17 F100.\nG0 X0 Y0\nM98 P1000 L3\nM98 P00022000\nM30\n"
      "O1000 (STEP)\nG91 G1 X1.\nG90\nM99\nO2000\nM98 P3000\nG91 G1 Y10.\nG90\nM99\nO3000\nG91 G1 Z-1.\nG90\nM99\n%\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 8u);
  EXPECT_EQ(e[3], Vec3(3, 0, 0));
  EXPECT_EQ(e[4], Vec3(3, 0, -1));  // O2000 (twice, the older P0002 2000 form) calls O3000 first
  EXPECT_EQ(e[5], Vec3(3, 10, -1));
  EXPECT_EQ(e[7], Vec3(3, 20, -2));
  EXPECT_EQ(r.blocks[1].location.line, 9);  // the subprogram's line
  EXPECT_EQ(error_of("O0001\nG0 X0\nM98 P9010\nM30\n"),
            "p.nc:3:1: M98 P9010: subprogram O9010 is not in this file (dialect fanuc); Kontur reads one file: put "
            "the subprogram after the main program's end");
  EXPECT_EQ(error_of("O0001\nM98 P2\nM30\nO2\nG0 X1\n"),
            "p.nc:2:1: M98 P2: the subprogram runs to the end of the file without M99 (dialect fanuc)");
}

TEST(GcodeFanucDialect, G65PassesArgumentsAsLocalVariablesOfItsOwnLevel) {
  const auto r = read(
      "O1\nG21 G90 F100.\n#1 = 5\nG65 P9001 X10. Y20. R3. A2.\nG1 Z-#1\nM30\nO9001\n"
      "IF [#2 NE #0] THEN #3000 = 1 (B GIVEN)\nG1 X[#24 + #1] Y#25 Z-#18\nM99\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0], Vec3(12, 20, -3));  // X -> #24, A -> #1, R -> #18
  EXPECT_EQ(e[1], Vec3(12, 20, -5));  // the caller's #1 again
  EXPECT_EQ(error_of("O1\nG65 P9001 B1.\nM30\nO9001\nIF [#2 NE #0] THEN #3000 = 1 (B GIVEN)\nM99\n"),
            "p.nc:5:20: #3000=1: the program raises macro alarm 3001 B GIVEN (dialect fanuc)");
}

TEST(GcodeFanucDialect, HaasM97RunsALocalSubprogramAtAnNNumber) {
  const auto r =
      read("%\nO00002\nG21 G90 F100.\nM97 P100 L2\nG1 X0 Y0\nM30\nN100 G91 G1 X5.\nG90\nM99\n%\n", Dialect::haas);
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[1], Vec3(10, 0, 0));
  EXPECT_EQ(e[2], Vec3(0, 0, 0));
}

TEST(GcodeFanucDialect, M99InTheMainProgramEndsItWithAWarning) {
  const auto r = read("G21 F100.\nG1 X1.\nM99\nG1 X2.\n");
  ASSERT_EQ(ends(r).size(), 1u);
  EXPECT_TRUE(has_warning(r, "p.nc:3:1: warning: M99 in the main program: a fanuc control starts the program again"));
}

TEST(GcodeFanucDialect, SystemVariablesReadTheMachineState) {
  const auto r = read(
      "G21 G90 G17 F250.\nG10 L2 P2 X100. Y50. Z-10.\nG55\nG1 X5. Y6. Z7.\n#1 = #5001\n#2 = #5022\n"
      "#3 = #5243\n#4 = #4001 + #4003 + #4014\n#5 = #4109\n#5241 = 200.\nG1 X#1 Y#2 Z#3\nG1 X#4 Y#5\nG1 X#5241\n"
      "#6 = #2001\nG91 G1 X#6\nM30\n");
  const auto e = ends(r);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[0], Vec3(105, 56, -3));                 // machine = G55 offset + program
  EXPECT_EQ(e[1], Vec3(200 + 5, 50 + 56, -10 - 10));  // #5241 = 200 moved the G55 frame; X5 Y56 Z-10 in it
  EXPECT_EQ(e[2], Vec3(200 + 1 + 90 + 55, 50 + 250, -20));
  EXPECT_TRUE(has_warning(r, "#2001: tool offsets and tool data are not modelled: read as 0"));
  EXPECT_EQ(error_of("#5001 = 3\n"), "p.nc:1:1: #5001=3: #5001 is read-only (dialect fanuc)");
  EXPECT_EQ(error_of("#1 = #5061\n"), "p.nc:1:6: #5061: a system variable Kontur does not read (dialect fanuc)");
  const auto s = read("G21\n#3006 = 1 (CHECK TOOL)\nG0 X1\nM30\n");
  EXPECT_TRUE(has_warning(s, "p.nc:2:1: warning: #3006=1: the program stops here with the message 'CHECK TOOL'"));
}

TEST(GcodeFanucDialect, G91G28Z0GoesStraightUpToTheReferencePosition) {
  const auto r = read("G21 G90 G54 F100.\nG10 L2 P1 Z-50.\nG0 X10. Y20. Z5.\nG91 G28 Z0\nG90\n");
  ASSERT_EQ(r.blocks.size(), 3u);
  EXPECT_EQ(r.blocks[1].end, Vec3(10, 20, -45));  // through the intermediate point (here: where it is)
  EXPECT_EQ(r.blocks[2].type, BlockType::rapid);
  EXPECT_EQ(r.blocks[2].end, Vec3(10, 20, 0));  // Z to the reference position, X and Y stay
}

TEST(GcodeFanucDialect, AMotionCodeBesideG28OnlySetsTheMode) {
  // 'G00 G91 G28 Z0': G28 moves; G00 is the mode of the blocks after it
  const auto r = read("G21 G90 F100.\nG1 X5. Y5. Z-3.\nG00 G91 G28 Z0\nG90 X10.\nM30\n");
  ASSERT_EQ(r.blocks.size(), 4u);
  EXPECT_EQ(r.blocks[2].end, Vec3(5, 5, 0));
  EXPECT_EQ(r.blocks[3].type, BlockType::rapid);
  EXPECT_EQ(r.blocks[3].end, Vec3(10, 5, 0));
  // a block with its own motion code keeps it
  const auto s = read("G21 G90 F100.\nG00 G91 G28 Z0\nG90 G1 X10.\nM30\n");
  EXPECT_EQ(s.blocks.back().type, BlockType::line);
}

TEST(GcodeFanucDialect, CyclesG84G85G86G89ExpandIntoTheirMoves) {
  const std::string head = "G21 G90 G17 G98 F100.\nG0 X0 Y0 Z10.\n";
  struct Case {
    const char* cycle;
    std::vector<std::pair<BlockType, double>> moves;  // type and end Z of each block after the rapid to the hole
  };
  const std::vector<Case> cases = {
      {"G84", {{BlockType::line, -5}, {BlockType::dwell, -5}, {BlockType::line, 2}, {BlockType::rapid, 10}}},
      {"G85", {{BlockType::line, -5}, {BlockType::line, 2}, {BlockType::rapid, 10}}},
      {"G86", {{BlockType::line, -5}, {BlockType::rapid, 10}}},
      {"G89", {{BlockType::line, -5}, {BlockType::dwell, -5}, {BlockType::line, 2}, {BlockType::rapid, 10}}},
  };
  for (const Case& c : cases) {
    const auto r = read(head + c.cycle + " X5. Y5. Z-5. R2. P500\nG80\nM30\n");
    ASSERT_EQ(r.blocks.size(), 3 + c.moves.size()) << c.cycle;  // G0, rapid over the hole, rapid to R
    EXPECT_EQ(r.blocks[1].end, Vec3(5, 5, 10)) << c.cycle;
    EXPECT_EQ(r.blocks[2].end, Vec3(5, 5, 2)) << c.cycle;
    for (std::size_t i = 0; i < c.moves.size(); ++i) {
      const Block& b = r.blocks[3 + i];
      EXPECT_EQ(b.type, c.moves[i].first) << c.cycle << " " << i;
      EXPECT_DOUBLE_EQ(b.end.z(), c.moves[i].second) << c.cycle << " " << i;
      if (b.type == BlockType::dwell) {
        EXPECT_DOUBLE_EQ(b.dwell_s, 0.5) << c.cycle;  // P500: milliseconds
      }
    }
  }
  // K repeats (incremental), G99 back to R
  const auto k = read("G21 G90 G17 G99 F100.\nG0 X0 Y0 Z10.\nG91 G85 X10. Z-7. R-8. K3\nG80\nM30\n");
  EXPECT_EQ(k.blocks.back().end, Vec3(30, 0, 2));
  EXPECT_EQ(error_of("G21 F100.\nG76 X1. Y1. Z-1. R1. Q1.\n"),
            "p.nc:2:1: G76: the fine boring cycle (oriented spindle stop and shift) is not supported (dialect fanuc)");
  // LinuxCNC still refuses G85 (its reading is unchanged)
  EXPECT_NE(error_of("G21 F100.\nG85 X1 Z-1 R1\n", Dialect::linuxcnc).find("canned cycles G85-G89"), std::string::npos);
}

TEST(GcodeFanucDialect, NoOpCodesAreWarnedAndModalMacroCallsRefused) {
  const auto r = read("G21 F100.\nG05.1 Q1\nG08 P1\nG10 L12 P1 R5.\nG4 P250\nG4 X1.5\nG1 X1.\nM30\n");
  ASSERT_EQ(r.blocks.size(), 3u);
  EXPECT_DOUBLE_EQ(r.blocks[0].dwell_s, 0.25);
  EXPECT_DOUBLE_EQ(r.blocks[1].dwell_s, 1.5);
  EXPECT_TRUE(has_warning(r, "p.nc:2:1: warning: G05.1 Q1: look-ahead"));
  EXPECT_FALSE(has_warning(r, "G10 L12"));  // the D register is written (tool compensation)
  const auto h = read("G21 F100.\nG187 P1 E0.01\nG1 X1.\nM30\n", Dialect::haas);
  EXPECT_TRUE(has_warning(h, "G187: accuracy control"));
  EXPECT_EQ(error_of("G21\nG66 P9010 X1.\n"), "p.nc:2:1: G66: modal macro calls are not supported (dialect fanuc)");
  const auto l20 = read("G21 F100.\nG10 L20 P1 X5.\nG1 X1.\nM30\n");
  ASSERT_EQ(l20.blocks.size(), 1u);
  EXPECT_EQ(l20.blocks[0].end, Vec3(1, 0, 0));
  EXPECT_TRUE(has_warning(l20, "p.nc:2:1: warning: G10 L20: the additional work offsets (G54.1 Pn) are not modelled"));
  EXPECT_EQ(error_of("G21\nG54.1 P3\n", Dialect::mitsubishi),
            "p.nc:2:1: G54.1: additional work coordinate systems (G54.1 Pn, Haas G154 Pn) are not supported (dialect "
            "mitsubishi)");
  EXPECT_EQ(error_of("G21\nG10 L2 P0 X1.\n"),
            "p.nc:2:1: G10 L2 P0: the external work offset (EXT, shifting every work system) is not supported (dialect "
            "fanuc)");
  EXPECT_EQ(error_of("G21\nG1 X1. ; comment\n"),
            "p.nc:2:8: ';': ends the block here (it is no comment in dialect fanuc); write comments in ( )");
  EXPECT_EQ(read("G21 F100.\nG1 X1. ; a comment\nM30\n", Dialect::mach3).blocks.size(), 1u);
}

TEST(GcodeFanucDialect, Mach3ReadsItsOlderUnitCodesAndTheG92Variables) {
  const auto r = read(
      "G71 G90 F100\nG0 X10 Y4\nG92 X0 Y0\n#1 = #5211\n#2 = #5212\nG1 X#1 Y#2\nM98 P100\nM30\nO100\n"
      "G91 G1 Z-1\nG90\nM99\n",
      Dialect::mach3);
  ASSERT_EQ(r.blocks.size(), 3u);
  EXPECT_EQ(r.blocks[1].end, Vec3(20, 8, 0));  // X10 Y4 in the G92 frame, whose offset is (10, 4)
  EXPECT_EQ(r.blocks[2].end, Vec3(20, 8, -1));
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
  // its parameters are LinuxCNC's: any number below #5000, 0 until set
  const auto p = read("G21 G90 F100\nG1 Y5\n#1000 = 7\nG1 X#1000 Y#2\nM30\n", Dialect::mach3);
  ASSERT_EQ(p.blocks.size(), 2u);
  EXPECT_EQ(p.blocks[1].end, Vec3(7, 0, 0));  // Y#2 is Y0, not left out
}

TEST(GcodeFanucDialect, PortOutputIsIgnoredWithAWarning) {
  const auto r = read("G21 F100.\nPOPEN\nDPRNT[DATE*(AAMMDD):*#3011]\nPCLOS\nG1 X1.\nM30\n", Dialect::haas);
  ASSERT_EQ(r.blocks.size(), 1u);
  ASSERT_EQ(r.warnings.size(), 3u);
  EXPECT_EQ(r.warnings[1], "p.nc:3:1: warning: DPRNT: output to a port, ignored (it does not move the axes)");
  // a loop not run skips it unread
  EXPECT_EQ(read("WHILE [1 EQ 2] DO1\nN5 DPRNT[A:*#1]\nEND1\nM30\n", Dialect::haas).warnings.size(), 0u);
}

TEST(GcodeFanucDialect, EveryRefusalNamesTheLineTheFeatureAndTheDialect) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"G21\nG74 X1. Z-1. R1.\n", "p.nc:2:1: G74: the left-hand tapping cycle is not supported (dialect fanuc)"},
      {"G21\nG87 X1. Z-1. R1.\n", "p.nc:2:1: G87: the back boring cycle is not supported (dialect fanuc)"},
      {"G21\nG68 X0 Y0 R30.\n", "p.nc:2:1: G68: coordinate system rotation is not supported (dialect fanuc)"},
      {"G21\nG51 X0 Y0 P2\n", "p.nc:2:1: G51: scaling is not supported (dialect fanuc)"},
      {"G21\nG51.1 X0\n", "p.nc:2:1: G51.1: programmable mirror image is not supported (dialect fanuc)"},
      {"G21\nG16\n", "p.nc:2:1: G16: polar coordinate programming is not supported (dialect fanuc)"},
      {"G21\nG31 X1. F100.\n", "p.nc:2:1: G31: the skip function (probing) is not supported (dialect fanuc)"},
      {"G21\nG50 X100. Z50.\n",
       "p.nc:2:1: G50: the lathe's coordinate system setting (G50 X Z) is not supported (dialect fanuc)"},
      {"G21\nG50 S2000\n",
       "p.nc:2:1: G50 S: the lathe's spindle speed limit: lathe programs (X as a diameter, feed per revolution) are "
       "not supported (dialect fanuc)"},
      {"#1=1\nIF [#1 EQ 1] THEN G0 X1.\n",
       "p.nc:2:19: IF .. THEN: only an assignment #i = .. may follow THEN (dialect fanuc)"},
      {"#1 = #7001\n", "p.nc:1:6: #7001: a system variable Kontur does not read (dialect fanuc)"},
      {"#7001 = 1.\n", "p.nc:1:1: #7001=1: a system variable Kontur does not write (dialect fanuc)"},
      {"#1=1\nG1 X#1+2.\n",
       "p.nc:2:7: 'X#1+2.': arithmetic in a word needs brackets (dialect fanuc reads X#i or X[expression])"},
      {"G21\nM97 P10\n",
       "p.nc:2:1: M97: Haas's local subprogram call is not this control's: read the program with --dialect haas "
       "(dialect fanuc)"},
      {"O1\nM98 P2\nM30\nO2\nG0 X1.\nO3\nM99\n",
       "p.nc:2:1: M98 P2: the subprogram runs into the next program O3 on line 6 without M99 (dialect fanuc)"},
  };
  for (const auto& [program, message] : cases) EXPECT_EQ(error_of(program), message) << program;
  EXPECT_EQ(error_of("G21\nM97 P10\nM30\n", Dialect::haas),
            "p.nc:2:1: M97 P10: no block N10 in this file (dialect haas)");
}

TEST(GcodeFanucDialect, IntegerAxisWordsAreWholeUnitsWithOneWarningForFanuc) {
  const auto r = read("G21 G90 F100\nG1 X0 Y100\nG1 X25\nM30\n");
  ASSERT_EQ(r.blocks.size(), 2u);
  EXPECT_DOUBLE_EQ(r.blocks[0].end.y(), 100.0);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0],
            "p.nc:2:7: warning: Y100: written without a decimal point, read as 100 mm; a fanuc with parameter 3401#0 "
            "DPI=0 reads it as 100 least increments (0.1 mm) (warned once)");
  EXPECT_TRUE(read("G21 G90 F100\nG1 X0 Y100\nM30\n", Dialect::haas).warnings.empty());
}

TEST(GcodeFanucDialect, AHaasStyleProgramReads) {
  const auto r = read(
      "%\nO00001 (PART)\n(HAAS VF-2)\nT1 M06\nG00 G17 G40 G49 G80 G90\nG54 X0. Y0. S1500 M03\n"
      "G43 H01 Z25. M08\nG81 G99 X10. Y10. Z-5. R2. F200.\nX20.\nM98 P00002\nG80\nG00 Z25.\n"
      "G91 G28 Z0.\nG90\nM05\nM30\n\nO00002 (PATTERN)\nG90 X30. Y10.\nX40.\nM99\n%\n",
      Dialect::haas);
  ASSERT_FALSE(r.blocks.empty());
  int holes = 0;
  for (const Block& b : r.blocks)
    if (b.type == BlockType::line && b.end.z() == -5.0) ++holes;
  EXPECT_EQ(holes, 4);                              // X10, X20, and the subprogram's X30, X40 in the still active cycle
  EXPECT_EQ(r.blocks.back().end, Vec3(40, 10, 0));  // G28 Z to the reference position
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
}

}  // namespace
}  // namespace kontur::gcode
