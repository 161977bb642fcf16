// What the reader makes of the tool table: tool length compensation applied to Z (G43 H, G43.1,
// G43.2, G49), G10 L1 / L10 / L11 writing the run's table, the Fanuc family's H and D registers
// (G10 L10..L13), and the cutter compensation modal state the compensation stage reads (G41 / G42 D,
// G41.1 / G42.1 D, G40) with its refusals.
#include <gtest/gtest.h>
#include <kontur/geometry/helix_arc.hpp>
#include <variant>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/gcode/tool_table.hpp>

#include <fmt/format.h>

#include <memory>
#include <string>
#include <vector>

namespace kontur::gcode {
namespace {

// ---------------------------------------------------------------- the reader

std::shared_ptr<const ToolTable> table(const std::string& text) {
  return std::make_shared<const ToolTable>(ToolTable::parse(text, "t.tbl"));
}

std::vector<Block> read(const std::string& program, std::shared_ptr<const ToolTable> tools = {},
                        Dialect dialect = Dialect::linuxcnc) {
  ReaderOptions o;
  o.dialect = dialect;
  o.tool_table = std::move(tools);
  Reader reader("p.ngc", program, o);
  std::vector<Block> blocks;
  Block b;
  while (reader.next(b)) blocks.push_back(b);
  return blocks;
}

std::string error_of(const std::string& program, std::shared_ptr<const ToolTable> tools = {},
                     Dialect dialect = Dialect::linuxcnc) {
  try {
    read(program, std::move(tools), dialect);
  } catch (const InputError& e) {
    // without the " (dialect linuxcnc)" every message ends with
    std::string m = e.what();
    const std::string suffix = fmt::format(" (dialect {})", to_string(dialect));
    if (m.size() > suffix.size() && m.compare(m.size() - suffix.size(), suffix.size(), suffix) == 0)
      m.resize(m.size() - suffix.size());
    return m;
  }
  return "";
}

TEST(ToolLength, G43AppliesTheToolsLengthToMachineZAndG49RemovesIt) {
  const auto b = read("G21 G90\nT2 M6\nG43 H2\nG0 Z5\nG1 X10 F100\nG49\nG0 Z5\nM2\n", table("T2 Z12.5 D6\n"));
  ASSERT_EQ(b.size(), 3u);
  EXPECT_DOUBLE_EQ(b[0].start.z(), 0.0);  // G43 does not move: the next move carries the offset
  EXPECT_DOUBLE_EQ(b[0].end.z(), 17.5);
  EXPECT_DOUBLE_EQ(b[0].modal.tool_length_mm, 12.5);
  EXPECT_TRUE(b[0].modal.tool_length_offset);
  EXPECT_EQ(b[0].modal.tool_length_h, 2);
  EXPECT_DOUBLE_EQ(b[1].end.z(), 17.5);
  EXPECT_DOUBLE_EQ(b[2].start.z(), 17.5);
  EXPECT_DOUBLE_EQ(b[2].end.z(), 5.0);
  EXPECT_DOUBLE_EQ(b[2].modal.tool_length_mm, 0.0);
  EXPECT_FALSE(b[2].modal.tool_length_offset);
}

TEST(ToolLength, G43WithoutHUsesTheCurrentToolAndInchProgramsKeepMm) {
  const auto b = read("G20 G90\nT3\nM6\nG43\nG0 Z1\nM2\n", table("T3 Z10\n"));
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 25.4 + 10.0);  // the table is in mm, the program in inches
}

TEST(ToolLength, WithoutATableG43IsLengthZero) {
  const auto b = read("G21\nG43 H7\nG0 Z5\nM2\n");
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 5.0);
  EXPECT_DOUBLE_EQ(b[0].modal.tool_length_mm, 0.0);
  EXPECT_TRUE(b[0].modal.tool_length_offset);
}

TEST(ToolLength, G43_1TakesTheLengthOfTheBlockAndG43_2AddsAnotherTool) {
  const auto b = read("G21\nG43.1 Z4\nG0 Z1\nG43.2 H1\nG0 Z2\nM2\n", table("T1 Z10\n"));
  ASSERT_EQ(b.size(), 2u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 5.0);
  EXPECT_DOUBLE_EQ(b[1].end.z(), 16.0);
  EXPECT_DOUBLE_EQ(b[1].modal.tool_length_mm, 14.0);
  // G43.1 needs its Z and cannot move in the same block
  EXPECT_NE(error_of("G21\nG43.1\n").find("p.ngc:2:1: G43.1: Z (the tool length) missing"), std::string::npos);
  EXPECT_NE(error_of("G21\nG43.1 G1 Z4 F10\n").find("G43.1 and G1 in one block"), std::string::npos);
}

TEST(ToolLength, G10L1WritesTheTableForTheRun) {
  const auto b = read("G21\nG10 L1 P4 Z3 R2\nG43 H4\nG0 Z0\nG41 D4\nG1 X5 F10\nM2\n");
  ASSERT_EQ(b.size(), 2u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 3.0);
  EXPECT_EQ(b[1].modal.cutter_comp, CutterComp::left);
  EXPECT_DOUBLE_EQ(b[1].modal.cutter_radius_mm, 2.0);
}

TEST(ToolLength, G10L10AndL11SetTheLengthFromTheCurrentPosition) {
  // at machine Z 20 (G54 Z offset 5): L10 makes the current position Z 0 with the work offset -> 15
  const auto b = read("G21\nG10 L2 P1 Z5\nG0 Z15\nG10 L10 P1 Z0\nG43 H1\nG0 X1\nG10 L11 P2 Z0\nG43 H2\nG0 X2\nM2\n");
  ASSERT_EQ(b.size(), 3u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 20.0);
  EXPECT_DOUBLE_EQ(b[1].end.z(), 20.0);  // the machine stays; program Z is 0 now
  EXPECT_DOUBLE_EQ(b[1].modal.tool_length_mm, 15.0);
  EXPECT_DOUBLE_EQ(b[2].modal.tool_length_mm, 20.0);  // L11: without the work offset
  EXPECT_DOUBLE_EQ(b[2].end.z(), 20.0);
}

TEST(ToolLength, ToolsNotInTheTableAreRefused) {
  const auto t = table("T1 Z1 D2\n");
  EXPECT_EQ(error_of("G21\nG43 H5\n", t), "p.ngc:2:5: G43 H5: tool 5 is not in the tool table");
  EXPECT_EQ(error_of("G21\nT9 M6\n", t), "p.ngc:2:1: T9: the tool is not in the tool table");
  EXPECT_EQ(error_of("G21\nG41 D3\n", t), "p.ngc:2:5: G41 D3: tool 3 is not in the tool table");
}

TEST(CutterCompensation, BlocksCarryTheSideAndTheRadiusAndAreOffset) {
  const auto b = read("G21 G17 F100\nT1 M6\nG41 D1\nG1 X10\nG2 X20 R5\nG40\nG1 X0\nG42.1 D4\nG1 Y10\nG40 G0 X0 Y0\nM2\n",
                      table("T1 D6 Z0\n"));
  ASSERT_EQ(b.size(), 5u);
  EXPECT_EQ(b[0].modal.cutter_comp, CutterComp::left);
  EXPECT_DOUBLE_EQ(b[0].modal.cutter_radius_mm, 3.0);
  // Offset by the reader's compensation stage: the entry line ends where it meets the arc's offset
  // (the G2 of radius 5 about (15, 0) grows to 8 on the left of a clockwise arc).
  EXPECT_EQ(b[0].start, Vec3(0, 0, 0));
  EXPECT_NEAR((b[0].end - Vec3(15, 0, 0)).norm(), 8.0, 1e-9);
  ASSERT_TRUE(std::holds_alternative<HelixArc>(b[1].geometry));
  EXPECT_NEAR(std::get<HelixArc>(b[1].geometry).radius_mm(), 8.0, 1e-12);
  EXPECT_NEAR((b[1].end - Vec3(23, 0, 0)).norm(), 0.0, 1e-9);  // the exit leaves from the offset end
  EXPECT_EQ(b[1].modal.cutter_comp, CutterComp::left);
  EXPECT_EQ(b[2].modal.cutter_comp, CutterComp::off);
  EXPECT_DOUBLE_EQ(b[2].modal.cutter_radius_mm, 0.0);
  EXPECT_EQ(b[3].modal.cutter_comp, CutterComp::right);
  EXPECT_DOUBLE_EQ(b[3].modal.cutter_radius_mm, 2.0);
  EXPECT_EQ(b[4].modal.cutter_comp, CutterComp::off);
}

TEST(CutterCompensation, WithoutATableOnlyTheDiameterInTheBlockWorks) {
  const auto b = read("G20 F10\nG41.1 D0.5\nG1 X1\nM2\n");
  ASSERT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(b[0].modal.cutter_radius_mm, 0.25 * 25.4);
  EXPECT_EQ(error_of("G21\nG42 D2\n"),
            "p.ngc:2:5: G42 D2: the radius of tool 2 is unknown: no tool table given (--tool-table FILE or the "
            "INI's [EMCIO] TOOL_TABLE; G41.1 / G42.1 D give the diameter in the block)");
}

TEST(CutterCompensation, RefusesWhatLinuxcncRefuses) {
  EXPECT_EQ(error_of("G21\nG41.1 D2\nG42.1 D2\n"),
            "p.ngc:3:1: G42.1: cutter radius compensation is already on (LinuxCNC: G40 before switching it on again)");
  EXPECT_EQ(error_of("G21\nG41.1 D2\nG19\n"),
            "p.ngc:3:1: G19: the plane cannot change while cutter radius compensation is on (G40 first)");
  EXPECT_EQ(error_of("G21\nG19\nG41.1 D2\n"),
            "p.ngc:3:1: G41.1: cutter radius compensation only in the XY (G17) or XZ (G18) plane");
  EXPECT_EQ(error_of("G21\nG41.1 D-2\n"), "p.ngc:2:7: G41.1 D-2: the diameter must be >= 0");
  EXPECT_EQ(error_of("G21\nG41.1\n"), "p.ngc:2:1: G41.1: D (the cutter diameter) missing");
  EXPECT_EQ(error_of("G21\nG41 D1.5\n", table("T1 D1\n")), "p.ngc:2:5: D1.5: the tool number must be an integer >= 0");
  EXPECT_EQ(error_of("G21 F10\nG41.1 D2\nG1 X10\nG40\nG2 X20 R5\n"),
            "p.ngc:5:1: G2: the move just after G40 (leaving cutter radius compensation) must be straight, not an arc "
            "(LinuxCNC's rule)");
  // a G40 in the same block turns compensation off before the plane changes; the same plane is no change
  EXPECT_EQ(error_of("G21\nG41.1 D2\nG40 G18\nG17\nG41.1 D2\nG17\nM2\n"), "");
}

TEST(FanucRegisters, G10WritesHAndDRegistersAndWearIsAdded) {
  const std::string program =
      "G21 F100.\nG10 L10 P5 R20.\nG10 L11 P5 R-0.5\nG10 L12 P5 R4.\nG10 L13 P5 R0.1\n"
      "G43 H5 G0 Z0.\nG41 D5 G1 X10.\nG91 G10 L12 P5 R1.\nG90 G40 G1 X0.\nG41 D5 G1 X10.\nM30\n";
  const auto b = read(program, {}, Dialect::fanuc);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 19.5);
  EXPECT_DOUBLE_EQ(b[1].modal.cutter_radius_mm, 4.1);  // a radius on Fanuc, plus wear
  EXPECT_DOUBLE_EQ(b[3].modal.cutter_radius_mm, 5.1);  // G91 G10: added to the geometry
}

TEST(FanucRegisters, TheLinuxcncTableFillsTheRegistersByToolNumber) {
  const auto b = read("G21 F100.\nG43 H2 G0 Z0.\nG42 D2 G1 X5.\nM30\n", table("T2 Z7 D8\n"), Dialect::haas);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_DOUBLE_EQ(b[0].end.z(), 7.0);
  EXPECT_DOUBLE_EQ(b[1].modal.cutter_radius_mm, 4.0);
  EXPECT_EQ(b[1].modal.cutter_comp, CutterComp::right);
  // Fanuc 0M writes the register with H beside G41 / G42 when there is no D
  const auto h = read("G21 F100.\nG42 H2 G1 X5.\nM30\n", table("T2 Z7 D8\n"), Dialect::fanuc);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_DOUBLE_EQ(h[0].modal.cutter_radius_mm, 4.0);
  EXPECT_DOUBLE_EQ(h[0].modal.tool_length_mm, 0.0);
}

}  // namespace
}  // namespace kontur::gcode
