// Every real program of ../shared/data/gcode is read. Those that use a feature Kontur deliberately
// does not run (or that break a rule a control checks) stop with the message naming it; the list
// is docs/gcode.md's "Shared programs" section. All others read to the end with finite geometry.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>

namespace kontur::gcode {
namespace {

const std::filesystem::path data_dir = std::filesystem::path(KONTUR_SHARED_DIR) / "data" / "gcode";

// Relative path -> substring of the expected message.
const std::map<std::string, std::string>& expected_errors() {
  static const std::map<std::string, std::string> m = {
      {"linuxcnc-nurbs/G5_Curva_Stella_n1-1_G5.ngc", ":12:1: G2.2: unknown G code"},
      {"linuxcnc-tp/diagnostic/bad_spirals_1.ngc", ":14:1: G3: radius to the start 12.7 mm and to the end 28.3981 mm"},
      {"linuxcnc-tp/diagnostic/bad_spirals_comp.ngc", ":13:1: G3: radius to the start 25.4 mm and to the end 15.24 mm"},
      {"linuxcnc-tp/diagnostic/bad_spirals_lathe.ngc", ":12:1: G3: radius to the start 12.7 mm and to the end 28.3981 mm"},
      {"linuxcnc-tp/diagnostic/spiral_aggressive.ngc", ":12:1: G2: radius to the start 5.08 mm and to the end 53.34 mm"},
      {"linuxcnc-tp/spindle/g33_blend.ngc", ":9:1: G33: spindle-synchronised motion"},
      {"linuxcnc-tp/spindle/g33_simple.ngc", ":4:1: G33: spindle-synchronised motion"},
      {"linuxcnc-tp/spindle/rigidtap_test.ngc", ":4:1: G33.1: spindle-synchronised motion"},
      {"linuxcnc-tp/spindle/tapping.ngc", ":4:1: G33.1: spindle-synchronised motion"},
      {"linuxcnc-tp/spindle/g95_blend.ngc", ":8:1: G95: feed per revolution G95"},
      {"linuxcnc-tp/violation_checks/tap-discrimant-error-orig.ngc", ":21:5: G7: lathe diameter mode G7"},
  };
  return m;
}

TEST(GcodeSharedPrograms, EveryProgramIsReadOrStopsWithItsMessage) {
  ASSERT_TRUE(std::filesystem::is_directory(data_dir)) << data_dir;
  int read_ok = 0, stopped = 0;
  std::map<std::string, bool> seen;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(data_dir)) {
    if (entry.path().extension() != ".ngc") continue;
    const std::string rel = std::filesystem::relative(entry.path(), data_dir).generic_string();
    const auto it = expected_errors().find(rel);
    try {
      const ProgramSummary s = check_program(entry.path().string());
      EXPECT_TRUE(it == expected_errors().end()) << rel << ": read, but expected: " << it->second;
      EXPECT_GT(s.lines, 0) << rel;  // (interp_state/sloc_toolchange.ngc has no motion at all)
      EXPECT_TRUE(std::isfinite(s.path_length_mm) && std::isfinite(s.rapid_length_mm)) << rel;
      ++read_ok;
    } catch (const InputError& e) {
      ASSERT_TRUE(it != expected_errors().end()) << rel << ": unexpected error: " << e.what();
      EXPECT_NE(std::string(e.what()).find(it->second), std::string::npos)
          << rel << "\n  expected: " << it->second << "\n  got:      " << e.what();
      ++stopped;
    }
    seen[rel] = true;
  }
  for (const auto& [rel, msg] : expected_errors()) EXPECT_TRUE(seen.count(rel)) << rel << " not found";
  EXPECT_EQ(stopped, static_cast<int>(expected_errors().size()));
  EXPECT_GE(read_ok, 155);
  std::printf("shared programs: %d read, %d stopped with their message\n", read_ok, stopped);
}

TEST(GcodeSharedPrograms, OWordSubroutinesAndLoops) {
  // O100 sub with a while loop of 1000 incremental moves, called twice
  const ProgramSummary s = check_program((data_dir / "linuxcnc-tp/quick-tests/straight_segments.ngc").string());
  EXPECT_EQ(s.by_type[static_cast<std::size_t>(BlockType::line)], 1002);
  EXPECT_EQ(s.by_type[static_cast<std::size_t>(BlockType::rapid)], 1003);
}

TEST(GcodeSharedPrograms, ThreeDChipsTotals) {
  const ProgramSummary s = check_program((data_dir / "3D_Chips.ngc").string());
  EXPECT_EQ(s.by_type[static_cast<std::size_t>(BlockType::line)], 4681);
  EXPECT_EQ(s.by_type[static_cast<std::size_t>(BlockType::rapid)], 3);
  EXPECT_NEAR(s.path_length_mm, 5814.068986, 1e-5);
}

TEST(GcodeSharedPrograms, NurbsProgramsGiveOneNurbsBlockPerCurve) {
  for (const char* name : {"G6_Curva_Farfalla_n1-1.ngc", "G6_Ruota_dentata_n1-1.ngc", "G5_butterfly-yz.ngc",
                           "G6_Curva_Mazatrol_n1-1-xy-yz-zx.ngc"}) {
    const ProgramSummary s = check_program((data_dir / "linuxcnc-nurbs" / name).string());
    EXPECT_GT(s.by_type[static_cast<std::size_t>(BlockType::nurbs)], 0) << name;
    EXPECT_GT(s.path_length_mm, 0.0) << name;
  }
}

}  // namespace
}  // namespace kontur::gcode
