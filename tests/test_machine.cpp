// Machine files: the embedded default, Kontur's TOML, LinuxCNC's INI (the shared test configs as
// they are), and every bad value named with file, field and rule.
#include <gtest/gtest.h>
#include <kontur/error.hpp>
#include <kontur/machine.hpp>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace kontur {
namespace {

namespace fs = std::filesystem;

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("kontur_test_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p;
}

void expect_error(const std::string& name, const std::string& text, const std::string& rule, const std::string& fragment) {
  const fs::path p = write_temp(name, text);
  try {
    (void)read_machine(p);
    ADD_FAILURE() << "accepted " << name;
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), rule) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << "names the file: " << e.what();
  }
  fs::remove(p);
}

TEST(Machine, DefaultIsValidAndMatchesTheBundledFile) {
  const Machine d = default_machine();
  EXPECT_NO_THROW(validate(d));
  const Machine f = read_machine(fs::path(KONTUR_SOURCE_DIR) / "examples" / "machines" / "default.toml");
  ASSERT_EQ(f.axes.size(), d.axes.size());
  for (std::size_t i = 0; i < d.axes.size(); ++i) {
    EXPECT_EQ(f.axes[i].name, d.axes[i].name);
    EXPECT_DOUBLE_EQ(f.axes[i].max_velocity, d.axes[i].max_velocity);
    EXPECT_DOUBLE_EQ(f.axes[i].max_acceleration, d.axes[i].max_acceleration);
    EXPECT_DOUBLE_EQ(f.axes[i].max_jerk, d.axes[i].max_jerk);
  }
  EXPECT_DOUBLE_EQ(f.max_feed_mm_s, d.max_feed_mm_s);
  EXPECT_DOUBLE_EQ(f.servo_period_s, d.servo_period_s);
  EXPECT_EQ(f.name, d.name);
}

TEST(Machine, LinuxCncTestConfigsReadAsTheyAre) {
  const fs::path dir = fs::path(KONTUR_SHARED_DIR) / "data" / "gcode" / "linuxcnc-tp" / "configs";
  if (!fs::exists(dir)) GTEST_SKIP() << dir << " not found (../shared beside the checkout)";
  int read = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".ini") continue;
    const Machine m = read_machine(entry.path());
    EXPECT_DOUBLE_EQ(m.servo_period_s, 1e-3) << entry.path();  // SERVO_PERIOD = 1000000 ns
    EXPECT_NE(m.axis('X'), nullptr) << entry.path();
    ++read;
    // Round trip through Kontur's TOML keeps every limit.
    const fs::path t = write_temp("roundtrip.toml", to_toml(m));
    const Machine r = read_machine(t);
    fs::remove(t);
    ASSERT_EQ(r.axes.size(), m.axes.size());
    for (std::size_t i = 0; i < m.axes.size(); ++i) {
      EXPECT_DOUBLE_EQ(r.axes[i].max_velocity, m.axes[i].max_velocity);
      EXPECT_DOUBLE_EQ(r.axes[i].max_acceleration, m.axes[i].max_acceleration);
      EXPECT_DOUBLE_EQ(r.axes[i].max_jerk, m.axes[i].max_jerk);
    }
  }
  EXPECT_EQ(read, 7);
  // XYZ.ini: LINEAR_UNITS = inch, X MAX_VELOCITY = 8 in/s, MAX_ACCELERATION = 30 in/s^2.
  const Machine xyz = read_machine(dir / "XYZ.ini");
  EXPECT_DOUBLE_EQ(xyz.axis('X')->max_velocity, 8 * 25.4);
  EXPECT_DOUBLE_EQ(xyz.axis('X')->max_acceleration, 30 * 25.4);
  EXPECT_DOUBLE_EQ(xyz.axis('X')->max_jerk, 30 * 25.4 / 0.01);  // no MAX_JERK: acceleration / 10 ms
  EXPECT_DOUBLE_EQ(xyz.axis('Z')->max_position, 10.0001 * 25.4);
  EXPECT_DOUBLE_EQ(xyz.max_feed_mm_s, 12 * 25.4);  // MAX_LINEAR_VELOCITY
  ASSERT_NE(xyz.axis('A'), nullptr);
  EXPECT_TRUE(xyz.axis('A')->rotary);
  EXPECT_DOUBLE_EQ(xyz.axis('A')->max_velocity, 25.0);  // [deg/s], not scaled by inch
  // XZ.ini: coordinates X Z, sections [AXIS_0] and [AXIS_2] (numbered by the letter).
  const Machine xz = read_machine(dir / "XZ.ini");
  EXPECT_EQ(xz.axis('Y'), nullptr);
  ASSERT_NE(xz.axis('Z'), nullptr);
}

TEST(Machine, TomlOverridesAndErrors) {
  const fs::path p = write_temp("fast.toml", "servo_period_s = 0.000125\nmax_feed_mm_min = 30000\n");
  const Machine m = read_machine(p);
  fs::remove(p);
  EXPECT_DOUBLE_EQ(m.servo_period_s, 125e-6);
  EXPECT_DOUBLE_EQ(m.max_feed_mm_s, 500.0);
  EXPECT_EQ(m.axes.size(), 3u);  // default axes kept

  expect_error("zero.toml", "[axes.X]\nmax_velocity = 0\nmax_acceleration = 1\nmax_jerk = 1\n", "limit-positive",
               "axis X max velocity [mm/s] = 0: must be finite and > 0");
  expect_error("syntax.toml", "servo_period_s = = 1\n", "toml-syntax", ":1:");
  expect_error("unknown.toml", "spindle = 3\n", "unknown-field", "unknown field \"spindle\"");
  expect_error("axisfield.toml", "[axes.X]\nmax_speed = 3\n", "unknown-field", "axes.X.max_speed");
  expect_error("axisname.toml", "[axes.Q]\nmax_velocity = 3\n", "axis-name", "axes.Q");
  expect_error("period.toml", "servo_period_s = 1.5\n", "servo-period-range", "must be in [10 us, 100 ms]");
  expect_error("nan.toml", "chord_tolerance_mm = \"fine\"\n", "not-a-number", "chord_tolerance_mm is not a number");
  expect_error("range.toml", "[axes.X]\nmax_velocity = 1\nmax_acceleration = 1\nmax_jerk = 1\nmin_position = 5\nmax_position = -5\n",
               "position-range", "min position 5 must be below max position -5");
}

// The INI's G-code settings: the dialect, the subroutine path (relative to the INI) and LinuxCNC's
// centre-format arc radius tolerances.
TEST(Machine, IniRs274ngcSettings) {
  const fs::path p = write_temp("rs274.ini",
                                "[RS274NGC]\nSUBROUTINE_PATH = subs:../lib\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0.001\n"
                                "CENTER_ARC_RADIUS_TOLERANCE_INCH = 0.0001\n[KONTUR]\nDIALECT = Haas\n"
                                "[TRAJ]\nCOORDINATES = X\n[AXIS_0]\nMAX_VELOCITY = 1\nMAX_ACCELERATION = 1\n");
  const Machine m = read_machine(p);
  fs::remove(p);
  EXPECT_EQ(m.dialect, gcode::Dialect::haas);
  ASSERT_EQ(m.subroutine_path.size(), 2u);
  EXPECT_EQ(m.subroutine_path[0], (p.parent_path() / "subs").string());
  EXPECT_EQ(m.subroutine_path[1], (p.parent_path().parent_path() / "lib").string());
  EXPECT_EQ(m.arc_radius_tolerance_mm, 0.001);
  EXPECT_EQ(m.arc_radius_tolerance_inch, 0.0001);
  expect_error("dialect.ini", "[KONTUR]\nDIALECT = okuma\n[TRAJ]\nCOORDINATES = X\n[AXIS_0]\nMAX_VELOCITY = 1\n"
               "MAX_ACCELERATION = 1\n", "dialect", "DIALECT = okuma: not a G-code dialect");
  expect_error("arctol.ini", "[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0\n[TRAJ]\nCOORDINATES = X\n[AXIS_0]\n"
               "MAX_VELOCITY = 1\nMAX_ACCELERATION = 1\n", "limit-positive", "CENTER_ARC_RADIUS_TOLERANCE_MM");
}

TEST(Machine, IniErrors) {
  expect_error("units.ini", "[TRAJ]\nLINEAR_UNITS = furlong\n", "linear-units", "LINEAR_UNITS = furlong");
  expect_error("noaxis.ini", "[TRAJ]\nCOORDINATES = X Y\n[AXIS_0]\nMAX_VELOCITY = 1\nMAX_ACCELERATION = 1\n",
               "axis-section", "no [AXIS_Y], [AXIS_1] or [JOINT_1] section for coordinate Y");
  expect_error("acc.ini", "[TRAJ]\nCOORDINATES = X\n[AXIS_0]\nMAX_VELOCITY = 1\n", "missing-key",
               "[AXIS_0] MAX_ACCELERATION is missing");
  expect_error("num.ini", "[TRAJ]\nCOORDINATES = X\n[AXIS_0]\nMAX_VELOCITY = fast\nMAX_ACCELERATION = 1\n",
               "not-a-number", "[AXIS_0] MAX_VELOCITY = fast is not a number");
  expect_error("zero.ini", "[TRAJ]\nCOORDINATES = X\n[AXIS_0]\nMAX_VELOCITY = 1\nMAX_ACCELERATION = 0\n",
               "limit-positive", "axis X max acceleration [mm/s^2] = 0");
  try {
    (void)read_machine("/nonexistent/machine.ini");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.rule(), "file-missing");
  }
}

TEST(Machine, ToolTableFromTheIniAndTheToml) {
  // LinuxCNC's [EMCIO] TOOL_TABLE, relative to the INI, in its LINEAR_UNITS
  const fs::path tbl = write_temp("tool.tbl", "T1 D0.25 Z1\n");
  const fs::path ini =
      write_temp("tools.ini", "[TRAJ]\nCOORDINATES = X\nLINEAR_UNITS = inch\n[AXIS_X]\nMAX_VELOCITY = 1\nMAX_ACCELERATION = 10\n"
                 "[EMCIO]\nTOOL_TABLE = " + tbl.filename().string() + "\n");
  const Machine m = read_machine(ini);
  EXPECT_EQ(m.tool_table, tbl.lexically_normal().string());
  EXPECT_DOUBLE_EQ(m.tool_table_mm_per_unit, 25.4);
  fs::remove(tbl);
  // a configuration copied without its table runs as without one (the shared XYZ.ini names sim.tbl)
  EXPECT_TRUE(read_machine(ini).tool_table.empty());
  fs::remove(ini);
  const fs::path toml = write_temp("tools.toml", "tool_table = \"t/mill.tbl\"\ntool_table_units = \"inch\"\n");
  const Machine t = read_machine(toml);
  EXPECT_EQ(t.tool_table, (toml.parent_path() / "t" / "mill.tbl").lexically_normal().string());
  EXPECT_DOUBLE_EQ(t.tool_table_mm_per_unit, 25.4);
  EXPECT_NE(to_toml(t).find("tool_table_units = \"inch\""), std::string::npos);
  fs::remove(toml);
  EXPECT_DOUBLE_EQ(default_machine().tool_table_mm_per_unit, 1.0);
  EXPECT_TRUE(default_machine().tool_table.empty());
  expect_error("tools_bad.toml", "tool_table_units = \"furlong\"\n", "tool-table", "tool_table_units");
}

}  // namespace
}  // namespace kontur
