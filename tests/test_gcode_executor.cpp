// The dialect-neutral executor fed words directly (no lexer, no dialect): blocks and their
// geometry, the modal state, the coordinate frames (work offsets, rotation, G92), the tables of
// codes by modal group, and the control-alarm messages, so that a new dialect only has to hand
// it the same words.
#include <gtest/gtest.h>
#include <kontur/error.hpp>

#include "../src/gcode/coordinate_frames.hpp"
#include "../src/gcode/executor.hpp"
#include "../src/gcode/modal_groups.hpp"

#include <cmath>
#include <deque>
#include <numbers>
#include <string>
#include <vector>

namespace kontur::gcode::detail {
namespace {

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-12) {
  EXPECT_NEAR((a - b).norm(), 0.0, tol) << "(" << a.transpose() << ") vs (" << b.transpose() << ")";
}

// An executor with its diagnostics and parameters, run on blocks of words.
struct Machine {
  Diagnostics diag{"exec.ngc", 10};
  ParameterTable params;
  Executor exec{diag, params};
  std::deque<Words> history;  // the words stay where they are (the executor refers to the last)
  std::vector<Block> blocks;

  void run(const Words& w) {
    diag.set_line(diag.line() + 1);
    history.push_back(w);
    exec.execute(history.back());
    for (auto& b : exec.blocks()) blocks.push_back(std::move(b));
    exec.blocks().clear();
  }
};

Words g(int code10, std::initializer_list<std::pair<char, double>> values = {}) {
  Words w;
  w.add_g(code10, 1);
  int col = 4;
  for (const auto& [letter, v] : values) w.set(letter, v, col += 4);
  w.first_column = 1;
  return w;
}

TEST(GcodeExecutor, TurnsWordsIntoBlocksWithGeometry) {
  Machine m;
  m.run(g(10, {{'X', 10.0}, {'F', 600.0}}));
  m.run(g(30, {{'X', 0.0}, {'Y', 10.0}, {'I', -10.0}}));
  ASSERT_EQ(m.blocks.size(), 2u);
  EXPECT_EQ(m.blocks[0].type, BlockType::line);
  expect_near(m.blocks[0].end, Vec3(10, 0, 0));
  EXPECT_DOUBLE_EQ(m.blocks[0].feed.value, 600.0);
  EXPECT_EQ(m.blocks[0].location.line, 1);
  EXPECT_EQ(*m.blocks[0].location.file, "exec.ngc");
  EXPECT_EQ(m.blocks[1].type, BlockType::arc);
  EXPECT_NEAR(*m.blocks[1].length_mm(), 5.0 * std::numbers::pi, 1e-12);
  EXPECT_EQ(m.exec.modal_state().motion_g10, 30);
  expect_near(m.exec.position(), Vec3(0, 10, 0));
}

TEST(GcodeExecutor, KeepsModalStateByGroup) {
  Machine m;
  Words w = g(200);        // G20
  w.add_g(910, 5);         // G91
  w.add_g(180, 9);         // G18
  w.add_m(8, 13);          // M8
  w.add_m(7, 16);          // M7 with M8: both
  w.set('S', 1200.0, 20);
  m.run(w);
  const ModalState& s = m.exec.modal_state();
  EXPECT_EQ(s.units, Units::inch);
  EXPECT_EQ(s.distance, DistanceMode::incremental);
  EXPECT_EQ(s.plane, Plane::zx);
  EXPECT_TRUE(s.mist);
  EXPECT_TRUE(s.flood);
  EXPECT_DOUBLE_EQ(s.spindle_rpm, 1200.0);
  m.run(g(0, {{'X', 1.0}}));  // incremental inch
  expect_near(m.blocks.back().end, Vec3(25.4, 0, 0));
}

TEST(GcodeExecutor, AppliesWorkOffsetsRotationAndG92) {
  Machine m;
  m.run(g(100, {{'L', 2.0}, {'P', 1.0}, {'X', 5.0}, {'R', 90.0}}));  // G10 L2 P1 X5 R90
  // the current point stays at the machine origin: in the new frame it is X0 Y5
  expect_near(m.exec.position(), Vec3(0, 5, 0), 1e-12);
  m.run(g(0, {{'X', 1.0}}));
  expect_near(m.blocks.back().end, Vec3(0, 1, 0), 1e-12);  // (1, 5) rotated by 90 degrees, plus X5
  m.run(g(920, {{'X', 0.0}}));                               // G92 X0: here is X0
  m.run(g(0, {{'X', 2.0}}));
  expect_near(m.blocks.back().end, Vec3(0, 3, 0), 1e-12);
  expect_near(m.exec.position(), Vec3(2, 5, 0));
  m.run(g(921));                                             // G92.1: the G92 offset is gone
  expect_near(m.exec.position(), Vec3(3, 5, 0), 1e-12);
}

TEST(GcodeExecutor, EndsAtM2) {
  Machine m;
  Words w;
  w.add_m(2, 1);
  w.first_column = 1;
  m.run(w);
  EXPECT_TRUE(m.exec.ended());
  EXPECT_TRUE(m.exec.program_end_seen());
}

TEST(GcodeExecutor, ReportsLikeAControlAlarm) {
  auto error_of = [](const Words& w) {
    Machine m;
    m.diag.set_line(4);
    try {
      m.run(w);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  Words two_motions = g(0);
  two_motions.add_g(10, 4);
  EXPECT_EQ(error_of(two_motions), "exec.ngc:5:4: G1: G0 and G1 in one block: both belong to modal group 1");
  EXPECT_EQ(error_of(g(10, {{'X', 1.0}})), "exec.ngc:5:1: G1: feed rate is zero (no F given before the first feed move)");
  EXPECT_EQ(error_of(g(330)), "exec.ngc:5:1: G33: spindle-synchronised motion (G33 threading, G33.1 rigid tapping) "
                              "is not supported by Kontur");
  Words a_in_cycle = g(810, {{'X', 1.0}, {'Z', -1.0}, {'R', 1.0}, {'F', 100.0}, {'A', 3.0}});
  EXPECT_EQ(error_of(a_in_cycle),
            "exec.ngc:5:24: G81 A3: extra axes (A B C U V W) are not supported in a canned cycle (LinuxCNC moves them "
            "before the first hole; move them in a block of their own)");
}

TEST(GcodeModalGroups, TablesSortCodesIntoTheirGroups) {
  EXPECT_EQ(g_code_info(10).group, g_motion);
  EXPECT_EQ(g_code_info(62).group, g_motion);
  EXPECT_EQ(g_code_info(53).group, g_spline_end);
  EXPECT_EQ(g_code_info(591).group, g_coordinate);
  EXPECT_EQ(g_code_info(990).group, g_retract);
  EXPECT_EQ(g_code_info(921).group, g_nonmodal);
  EXPECT_EQ(g_code_info(22).group, -1);
  EXPECT_EQ(g_code_info(950).group, -2);
  EXPECT_NE(std::string(g_code_info(950).unsupported).find("G95"), std::string::npos);
  EXPECT_EQ(m_code_info(30).group, m_stop);
  EXPECT_EQ(m_code_info(64).group, m_io);
  EXPECT_EQ(m_code_info(150).group, -2);
  EXPECT_EQ(m_code_info(99).group, -3);  // subprogram return: refused, never ignored
  EXPECT_EQ(m_code_info(96).group, -1);
}

TEST(GcodeModalGroups, CamSafetyLineG80G0KeepsTheMotion) {
  const Diagnostics diag("groups.ngc", 1);
  Words w;
  w.add_g(800, 1);
  w.add_g(0, 5);
  const BlockCodes codes = classify_codes(w, diag);
  EXPECT_EQ(codes.code(g_motion), 0);
  EXPECT_EQ(codes.column(g_motion), 5);
  EXPECT_EQ(codes.code(g_plane), -1);
}

TEST(GcodeCoordinateFrames, MachineAndProgramCoordinatesAreInverse) {
  CoordinateFrames f;
  f.set_offset(2, 0, 10.0);
  f.set_offset(2, 2, -3.0);
  f.set_rotation_deg(2, 30.0);
  f.shift_g92(1, 4.0, 1.0);  // program Y 4 becomes 1
  const Vec3 p(1.0, 2.0, 3.0);
  expect_near(f.to_program(f.to_machine(p, 2), 2), p, 1e-12);
  expect_near(f.to_machine(p, 1), p + Vec3(0, 3, 0), 1e-12);  // system 1: only G92
  const Vec3 m(7.0, 8.0, 9.0);
  const Vec3 off = f.offset_placing(m, p, 2);  // G10 L20: the offset that puts p at m
  for (int a = 0; a < 3; ++a) f.set_offset(2, a, off[a]);
  expect_near(f.to_machine(p, 2), m, 1e-12);
  f.save_g92();
  f.clear_g92(false);
  expect_near(f.to_machine(p, 1), p);
  f.restore_g92();
  expect_near(f.to_machine(p, 1), p + Vec3(0, 3, 0), 1e-12);
}

}  // namespace
}  // namespace kontur::gcode::detail
