// The tool table in LinuxCNC's format: parsing, units, and the errors with file, line and rule.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/tool_table.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace kontur::gcode {
namespace {

std::string parse_error(const std::string& text) {
  try {
    (void)ToolTable::parse(text, "t.tbl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ToolTable, ParsesLinuxcncLines) {
  const ToolTable t = ToolTable::parse(
      "T1 P1 D6.000 Z+10.000 ;end mill\n"
      "\n"
      "; a comment line\n"
      "z-2.5 t2 p7 d0.5 X0.1 I10 J20 Q3 A1 U2\r\n"
      "T3\n",
      "t.tbl");
  ASSERT_EQ(t.size(), 3u);
  const Tool* t1 = t.find(1);
  ASSERT_NE(t1, nullptr);
  EXPECT_EQ(t1->pocket, 1);
  EXPECT_DOUBLE_EQ(t1->diameter_mm, 6.0);
  EXPECT_DOUBLE_EQ(t1->length_mm, 10.0);
  const Tool* t2 = t.find(2);
  ASSERT_NE(t2, nullptr);
  EXPECT_EQ(t2->pocket, 7);
  EXPECT_DOUBLE_EQ(t2->length_mm, -2.5);
  EXPECT_DOUBLE_EQ(t2->diameter_mm, 0.5);
  EXPECT_DOUBLE_EQ(t.find(3)->length_mm, 0.0);
  EXPECT_EQ(t.find(4), nullptr);
}

TEST(ToolTable, ValuesAreInTheMachineUnits) {
  const ToolTable t = ToolTable::parse("T1 D0.25 Z1\n", "t.tbl", 25.4);
  EXPECT_DOUBLE_EQ(t.find(1)->diameter_mm, 6.35);
  EXPECT_DOUBLE_EQ(t.find(1)->length_mm, 25.4);
}

TEST(ToolTable, RefusesBrokenLinesWithFileLineAndRule) {
  EXPECT_EQ(parse_error("T1 Z1\nT2 K5\n"), "t.tbl:2: unknown-word: K5: unknown word (expected T P X Y Z A B C U V W D I J Q)");
  EXPECT_EQ(parse_error("T1 Z1\n\nT1 Z2\n"), "t.tbl:3: tool-twice: T1: the tool is in the table twice");
  EXPECT_EQ(parse_error("T1 D-3\n"), "t.tbl:1: negative-diameter: D-3: the diameter must be >= 0");
  EXPECT_EQ(parse_error("T1 Zabc\n"), "t.tbl:1: not-a-number: Zabc: the value is not a number");
  EXPECT_EQ(parse_error("T1 Z\n"), "t.tbl:1: not-a-number: Z: the value is not a number");
  EXPECT_EQ(parse_error("P1 Z1\n"), "t.tbl:1: tool-missing: T (the tool number) missing");
  EXPECT_EQ(parse_error("T1.5\n"), "t.tbl:1: tool-number: T1.5: the tool number must be an integer >= 0");
  try {
    (void)ToolTable::read("/nonexistent/kontur.tbl");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "tool-table");
    EXPECT_NE(std::string(e.what()).find("/nonexistent/kontur.tbl"), std::string::npos);
  }
}

TEST(ToolTable, ReadsAFile) {
  const auto path = std::filesystem::temp_directory_path() / "kontur_test_tool_table.tbl";
  std::ofstream(path) << "T5 P5 D10 Z-1 ;x\n";
  const ToolTable t = ToolTable::read(path);
  std::filesystem::remove(path);
  ASSERT_NE(t.find(5), nullptr);
  EXPECT_DOUBLE_EQ(t.find(5)->diameter_mm, 10.0);
}

}  // namespace
}  // namespace kontur::gcode
