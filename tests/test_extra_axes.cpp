// Extra axes (issue 14): A B C [deg] and U V W [mm] beside the tool point's X Y Z, through the
// planner, the sampler, the checker, the setpoint files and the machine files. They move linearly
// with the distance along a move; each axis keeps its own velocity, acceleration and jerk; a move
// of the extra axes alone runs over their distance (LinuxCNC's feed rule).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <kontur/error.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/io/setpoint_reader.hpp>
#include <kontur/io/setpoint_writer.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/verify/checker.hpp>
#include <numbers>
#include <random>
#include <sstream>

namespace kontur {
namespace {

using program::Move;
using trajectory::Setpoint;

Machine machine_with(const std::string& extra) {
  Machine m = default_machine();
  for (const char c : extra) {
    const bool rotary = c == 'A' || c == 'B' || c == 'C';
    m.axes.push_back({c, rotary, rotary ? 90.0 : 50.0, rotary ? 900.0 : 500.0, rotary ? 20000.0 : 10000.0});
  }
  return m;
}

// A move from (p, x) to (q, y) at `feed` [mm/s] (or [deg/s] for a move of A B C alone).
Move move_to(std::shared_ptr<const Curve> curve, const ExtraAxes& x, const ExtraAxes& y, double feed,
             long line_no = 1) {
  Move m = program::move_along(std::move(curve), feed, false, line_no);
  m.extra_start = x;
  m.extra_end = y;
  m.length_mm = program::path_length(m.length_mm, x, y, m.tool_still);
  if (m.tool_still) m.curve = std::make_shared<LineSegment>(m.curve->point(m.curve->u_min()), m.curve->point(m.curve->u_min()));
  m.type = "line";
  return m;
}

Move line(Vec3 a, Vec3 b, const ExtraAxes& x, const ExtraAxes& y, double feed, long line_no = 1) {
  return move_to(std::make_shared<LineSegment>(a, b), x, y, feed, line_no);
}

struct PlannedRun {
  std::vector<Setpoint> points;
  verify::Report report;
};

// Plans and samples `moves` in `layout`, checking every setpoint as the pipeline does.
PlannedRun run(const Machine& machine, std::vector<Move> moves, const AxisLayout& layout) {
  for (std::size_t i = 0; i < moves.size(); ++i) moves[i].id = static_cast<program::MoveId>(i);
  trajectory::Trajectory tr;
  plan::MotionPlanner planner(machine, tr);
  trajectory::Sampler sampler(tr, machine.servo_period_s, layout);
  verify::Checker checker(moves, machine, layout);
  PlannedRun r;
  Setpoint sp;
  auto drain = [&] {
    while (sampler.next(sp)) {
      r.points.push_back(sp);
      checker.add(sp);
    }
  };
  for (const Move& m : moves) {
    planner.push(m);
    drain();
  }
  planner.finish();
  drain();
  EXPECT_TRUE(sampler.done());
  r.report = checker.finish();
  return r;
}

void expect_passed(const PlannedRun& r, const Machine& m) {
  EXPECT_TRUE(r.report.passed(m)) << [&] {
    std::string s;
    for (const std::string& f : r.report.failures(m)) s += f + "\n";
    return s;
  }();
}

TEST(ExtraAxes, RotaryAxisMovesLinearlyAlongALineWithinItsOwnLimits) {
  const Machine m = machine_with("A");
  const AxisLayout layout = AxisLayout::from_letters("XYZA");
  // 10 mm of X with 180 deg of A: A (90 deg/s) binds, not the feed of 100 mm/s.
  const PlannedRun r = run(m, {line({0, 0, 0}, {10, 0, 0}, {}, {180, 0, 0, 0, 0, 0}, 100.0)}, layout);
  expect_passed(r, m);
  ASSERT_GT(r.points.size(), 2000u);
  EXPECT_GE(r.points.back().t_s, 180.0 / 90.0);
  EXPECT_EQ(r.points.back().position[3], 180.0);  // exact at the end
  EXPECT_EQ(r.points.back().position[0], 10.0);
  for (const Setpoint& p : r.points) EXPECT_NEAR(p.position[3], 18.0 * p.position[0], 1e-9);
  EXPECT_NEAR(r.report.max_velocity_ratio, 1.0, 1e-3);
  EXPECT_EQ(r.report.worst_velocity_axis, 'A');
}

TEST(ExtraAxes, AMoveOfTheExtraAxesAloneRunsOverTheirDistanceAtTheFeed) {
  const Machine m = machine_with("AW");
  const AxisLayout layout = AxisLayout::from_letters("XYZAW");
  // A alone: 90 deg at 30 deg/s (F1800 [deg/min]): about 3 s; X Y Z stand.
  const PlannedRun r = run(m, {line({1, 2, 3}, {1, 2, 3}, {}, {90, 0, 0, 0, 0, 0}, 30.0)}, layout);
  expect_passed(r, m);
  EXPECT_NEAR(r.points.back().t_s, 3.0, 0.1);
  EXPECT_EQ(r.points.back().position[3], 90.0);
  for (const Setpoint& p : r.points) EXPECT_EQ(layout.tool(p.position), Vec3(1, 2, 3));
  // W and A together: the feed applies to W's distance (LinuxCNC: U V W before A B C).
  const PlannedRun w = run(m, {line({0, 0, 0}, {0, 0, 0}, {}, {9, 0, 0, 0, 0, 20}, 10.0)}, layout);
  expect_passed(w, m);
  EXPECT_NEAR(w.points.back().t_s, 2.0, 0.1);
  EXPECT_EQ(w.points.back().position[4], 20.0);
  EXPECT_EQ(w.points.back().position[3], 9.0);
}

TEST(ExtraAxes, ACornerOfAnExtraAxisSlowsTheJunction) {
  const Machine m = machine_with("A");
  const AxisLayout layout = AxisLayout::from_letters("XYZA");
  // X goes straight on while A reverses: the junction is a corner for A.
  const PlannedRun r = run(m,
                    {line({0, 0, 0}, {20, 0, 0}, {}, {40, 0, 0, 0, 0, 0}, 50.0),
                     line({20, 0, 0}, {40, 0, 0}, {40, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0}, 50.0)},
                    layout);
  expect_passed(r, m);
  double v_junction = 1e9;
  for (const Setpoint& p : r.points)
    if (std::abs(p.position[0] - 20.0) < 0.05) v_junction = std::min(v_junction, p.v_mm_s);
  EXPECT_LT(v_junction, 1.0);
}

TEST(ExtraAxes, SeededRandomFourAndFiveAxisPathsKeepEveryLimitAndEndExactly) {
  std::mt19937_64 rng(1414);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 24; ++trial) {
    const bool five = trial % 2 == 1;
    Machine m = machine_with(five ? "AB" : "A");
    m.servo_period_s = trial % 3 == 0 ? 0.000125 : 0.001;
    const AxisLayout layout = AxisLayout::from_letters(five ? "XYZAB" : "XYZA");
    std::vector<Move> moves;
    Vec3 p = Vec3::Zero();
    ExtraAxes x{};
    const int n = 4 + static_cast<int>(rng() % 8);
    for (int k = 0; k < n; ++k) {
      ExtraAxes y = x;
      y[0] += 90.0 * U(rng);
      if (five) y[1] += 45.0 * U(rng);
      const double feed = 5.0 + 60.0 * (U(rng) + 1.0);
      switch (rng() % 4) {
        case 0: {  // a move of the rotary axes alone
          moves.push_back(line(p, p, x, y, feed, k + 1));
          break;
        }
        case 1: {  // a helix with the rotary axes
          CircleFrame f;
          f.centre = p + Vec3(3.0, 0.0, 0.0);
          f.e1 = Vec3(-1, 0, 0);
          f.e2 = Vec3(0, -1, 0);  // n x e1
          f.normal = Vec3(0, 0, 1);
          auto arc = std::make_shared<HelixArc>(f, 3.0, std::numbers::pi * (0.3 + U(rng) + 1.0), 2.0 * U(rng));
          const Vec3 q = arc->point(arc->u_max());
          moves.push_back(move_to(arc, x, y, feed, k + 1));
          p = q;
          break;
        }
        default: {  // a line with the rotary axes (sometimes only a short one)
          const Vec3 q = p + Vec3(U(rng), U(rng), U(rng)) * (rng() % 2 ? 20.0 : 0.05);
          moves.push_back(line(p, q, x, y, feed, k + 1));
          p = q;
        }
      }
      x = y;
    }
    const PlannedRun r = run(m, moves, layout);
    SCOPED_TRACE(trial);
    expect_passed(r, m);
    const Setpoint& end = r.points.back();
    EXPECT_LE((layout.tool(end.position) - p).norm(), 1e-9);
    EXPECT_EQ(layout.extra(end.position)[0], x[0]);
    if (five) {
      EXPECT_EQ(layout.extra(end.position)[1], x[1]);
    }
  }
}

TEST(ExtraAxes, CheckerFindsARotaryAxisOffItsMove) {
  const Machine m = machine_with("A");
  const AxisLayout layout = AxisLayout::from_letters("XYZA");
  std::vector<Move> moves = {line({0, 0, 0}, {10, 0, 0}, {}, {30, 0, 0, 0, 0, 0}, 20.0)};
  moves[0].id = 0;
  PlannedRun r = run(m, moves, layout);
  expect_passed(r, m);
  // The same setpoints against a move whose A ends at 31 deg: A is up to 1 deg off.
  moves[0].extra_end[0] = 31.0;
  verify::Checker c(moves, m, layout);
  for (const Setpoint& p : r.points) c.add(p);
  const verify::Report bad = c.finish();
  EXPECT_FALSE(bad.passed(m));
  EXPECT_NEAR(bad.max_extra_axis_error, 1.0, 1e-6);
  EXPECT_EQ(bad.worst_extra_axis, 'A');
}

TEST(ExtraAxes, SetpointFilesCarryTheAxesAndReadBack) {
  const AxisLayout layout = AxisLayout::from_letters("XYZAW");
  Setpoint s;
  s.t_s = 0.001;
  s.position = layout.from_tool(Vec3(1, 2, 3), {45.5, 0, 0, 0, 0, -7.25});
  s.v_mm_s = 12.5;
  s.source_line = 9;
  const auto dir = std::filesystem::temp_directory_path();
  for (const SetpointFormat f : {SetpointFormat::csv, SetpointFormat::binary}) {
    const auto path = dir / (f == SetpointFormat::csv ? "kontur_axes.csv" : "kontur_axes.bin");
    {
      std::ofstream out(path, std::ios::binary);
      SetpointWriter w(out, f, 0.001, layout);
      w.write(s);
    }
    if (f == SetpointFormat::csv) {
      std::ifstream in(path);
      std::string header;
      std::getline(in, header);
      EXPECT_EQ(header, "t,x,y,z,a,w,v,block");
    }
    const SetpointFile back = read_setpoints(path.string());
    EXPECT_EQ(back.layout, layout);
    ASSERT_EQ(back.samples.size(), 1u);
    EXPECT_EQ(back.samples[0].position, s.position);
    EXPECT_EQ(back.samples[0].source_line, 9);
    EXPECT_EQ(back.samples[0].v_mm_s, 12.5);
  }
  // X Y Z files keep version 1 and their header.
  std::ostringstream xyz;
  SetpointWriter w(xyz, SetpointFormat::csv, 0.001);
  EXPECT_EQ(xyz.str(), "t,x,y,z,v,block\n");
  // Axes out of order are refused with the rule.
  const auto bad = dir / "kontur_axes_bad.csv";
  std::ofstream(bad) << "t,x,y,z,w,a,v,block\n0,0,0,0,0,0,0,1\n";
  try {
    (void)read_setpoints(bad.string());
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("in that order"), std::string::npos) << e.what();
  }
}

TEST(ExtraAxes, LinuxcncIniWithNineAxes) {
  const auto path = std::filesystem::temp_directory_path() / "kontur_nine_axes.ini";
  std::string text = "[TRAJ]\nCOORDINATES = X Y Z A B C U V W\nLINEAR_UNITS = inch\nMAX_LINEAR_VELOCITY = 4\n"
                     "[EMCMOT]\nSERVO_PERIOD = 1000000\n";
  // 2.7's numbering by the letter: X = 0 .. C = 5, U = 6 .. W = 8
  for (int i = 0; i < 9; ++i) text += "[AXIS_" + std::to_string(i) + "]\nMAX_VELOCITY = 2\nMAX_ACCELERATION = 20\n";
  std::ofstream(path) << text;
  const Machine m = read_machine(path);
  ASSERT_EQ(m.axes.size(), 9u);
  EXPECT_EQ(m.axes[6].name, 'U');
  EXPECT_FALSE(m.axes[6].rotary);
  EXPECT_DOUBLE_EQ(m.axes[6].max_velocity, 2 * 25.4);  // linear: inch -> mm
  EXPECT_TRUE(m.axes[3].rotary);
  EXPECT_DOUBLE_EQ(m.axes[3].max_velocity, 2.0);  // rotary: deg, not scaled
  // An [AXIS_W] section while COORDINATES has no W: the file disagrees with itself.
  std::ofstream(path) << "[TRAJ]\nCOORDINATES = X Y Z\n[AXIS_X]\nMAX_VELOCITY = 2\nMAX_ACCELERATION = 20\n"
                         "[AXIS_Y]\nMAX_VELOCITY = 2\nMAX_ACCELERATION = 20\n[AXIS_Z]\nMAX_VELOCITY = 2\n"
                         "MAX_ACCELERATION = 20\n[AXIS_W]\nMAX_VELOCITY = 2\nMAX_ACCELERATION = 20\n";
  try {
    (void)read_machine(path);
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("[AXIS_W]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kontur

namespace kontur {
namespace {

// Seeded random 4- and 5-axis programs as G-code, through the whole pipeline (reader, program
// stage, planner, sampler, checker): lines and rapids with A (and B), arcs and helices turning A,
// moves of the rotary axes alone, inverse-time (G93) blocks, and a NURBS (G5.2) between them. Every
// run keeps every axis's limits, every setpoint on its move (the extra axes included), and ends
// exactly (1e-9) where the program ends.
TEST(ExtraAxes, SeededRandomFourAndFiveAxisProgramsRunAndPass) {
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const auto dir = std::filesystem::temp_directory_path();
  for (int trial = 0; trial < 12; ++trial) {
    const bool five = trial % 2 == 1;
    Machine m = machine_with(five ? "AB" : "A");
    if (trial % 3 == 0) m.servo_period_s = 0.000125;
    std::ostringstream g;
    g << "G21 G90 G17 G94 G64 P0.01\nG0 X0 Y0 Z5 A0" << (five ? " B0" : "") << "\nF1200\n";
    double x = 0, y = 0, a = 0, b = 0;
    const int n = 6 + static_cast<int>(rng() % 10);
    for (int k = 0; k < n; ++k) {
      const double da = std::round(900.0 * U(rng)) / 10.0, db = five ? std::round(450.0 * U(rng)) / 10.0 : 0.0;
      a += da;
      b += db;
      std::ostringstream ab;
      ab << " A" << a << (five ? " B" + std::to_string(b) : "");
      switch (rng() % 6) {
        case 0:  // the rotary axes alone, in deg/min
          g << "G1" << ab.str() << " F" << 600 + rng() % 3000 << "\n";
          break;
        case 1: {  // an arc turning the rotary axes (a full quarter around a centre 5 mm away)
          const double nx = x + 5.0, ny = y + 5.0;
          const bool along_x = rng() % 2 == 1;  // the centre at (x + 5, y) or (x, y + 5)
          g << (rng() % 2 ? "G2" : "G3") << " X" << nx << " Y" << ny << " I" << (along_x ? 5 : 0) << " J"
            << (along_x ? 0 : 5) << ab.str() << " F" << 300 + rng() % 1500 << "\n";
          x = nx;
          y = ny;
          break;
        }
        case 2: {  // inverse time: the block takes 1/F minutes
          x += 10.0 * U(rng);
          y += 10.0 * U(rng);
          g << "G93 G1 X" << x << " Y" << y << ab.str() << " F" << 30 + rng() % 300 << "\nG94\n";
          break;
        }
        case 3: {  // a rapid
          x += 20.0 * U(rng);
          g << "G0 X" << x << ab.str() << "\n";
          break;
        }
        case 4: {  // a NURBS of the tool path (the rotary axes stand: control points are X Y Z)
          a -= da;
          b -= db;
          g << "G5.2 X" << x << " Y" << y << " P1 L3\nX" << x + 4 << " Y" << y + 6 << " P1\nX" << x + 8 << " Y"
            << y - 3 << " P2\nX" << x + 12 << " Y" << y << " P1\nG5.3\n";
          x += 12;
          break;
        }
        default: {  // a line with the rotary axes
          x += 15.0 * U(rng);
          y += 15.0 * U(rng);
          g << "G1 X" << x << " Y" << y << ab.str() << "\n";
        }
      }
    }
    g << "M2\n";
    const auto path = dir / ("kontur_random_axes_" + std::to_string(trial) + ".ngc");
    std::ofstream(path) << g.str();
    SCOPED_TRACE(g.str());
    Pipeline pipeline(m);
    const RunResult r = pipeline.run(path.string());
    EXPECT_TRUE(r.passed) << r.summary_json.substr(0, 1500);
    EXPECT_LE(r.check.end_error_mm, 1e-9);
    EXPECT_EQ(pipeline.layout().letters(), five ? "XYZAB" : "XYZA");
    std::filesystem::remove(path);
  }
}

// prepare() learns the columns in the reader's validating pass and run() does not validate again;
// a program file changed in between must be validated again, not streamed unchecked.
TEST(ExtraAxes, PrepareLearnsTheMovedAxesAndRunValidatesAProgramChangedSince) {
  const auto path = (std::filesystem::temp_directory_path() / "kontur_prepare_then_edit.ngc").string();
  std::ofstream(path) << "G21 G90 G17\nG1 X10 A30 F600\nG1 X20 Y5\nM2\n";
  Pipeline pipeline(machine_with("AW"));
  EXPECT_EQ(pipeline.prepare(path), AxisLayout::from_letters("XYZA"));  // W stays: the program does not move it
  long setpoints = 0;
  PipelineEvents events;
  events.setpoint = [&](const Setpoint&) { ++setpoints; };
  const RunResult first = pipeline.run(path, events);
  EXPECT_TRUE(first.passed);
  EXPECT_GT(setpoints, 0);
  // Prepared, then edited (longer, with an error on line 8 after dwells that would hand out setpoints
  // before it; the size differs, whatever the clock's resolution): run() validates it again and throws
  // before handing out any setpoint.
  (void)pipeline.prepare(path);
  std::ofstream(path) << "G21 G90 G17\nG1 X10 A30 F600\nG4 P0.5\nG1 X20\nG4 P0.5\nG1 X30\nG4 P0.5\nG1 X40 Y5 Q\nM2\n";
  setpoints = 0;
  try {
    (void)pipeline.run(path, events);
    FAIL() << "an edited program with an error ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":8:"), std::string::npos) << e.what();
  }
  EXPECT_EQ(setpoints, 0);
  // A prepare() that finds the error leaves nothing validated behind: run() of the unchanged file
  // finds it again (the kept blocks of the first version are not run).
  EXPECT_THROW((void)pipeline.prepare(path), InputError);
  EXPECT_THROW((void)pipeline.run(path, events), InputError);
  EXPECT_EQ(setpoints, 0);
  std::filesystem::remove(path);
}

// A linear axis the machine lacks (LinuxCNC's XY.ini has COORDINATES X Y) cannot move either: a
// block whose path runs along it is refused before any setpoint, naming the file, line, axis and
// the machine's axes. Until 2026-12-04 only A B C U V W were; a path along Z on XY.ini got a speed
// cap of zero from the planner, and its setpoints jumped (the check then found X at 125 times its
// velocity). A path in the plane the machine has runs, also after moves that leave Z where it is.
TEST(ExtraAxes, AMoveAlongALinearAxisTheMachineLacksIsRefused) {
  Machine xy = default_machine();
  xy.axes.pop_back();  // X Y: no Z
  const auto path = (std::filesystem::temp_directory_path() / "kontur_missing_linear_axis.ngc").string();
  const std::pair<const char*, const char*> refused[] = {
      {"G21 G90 G17\nG1 X10 F600\nG1 X20 Z5\nM2\n", ":3: the block moves Z (to 5)"},             // a line
      {"G21 G90 G17\nG1 X10 F600\nG2 X10 Y0 Z2 I5 J0\nM2\n", ":3: the block moves Z (to 2)"},  // a helix
      {"G21 G90 G18\nG1 X10 F600\nG2 X10 Z0 I5 K0\nM2\n", ":3: the block moves Z (to 0)"},     // a circle in XZ
  };
  for (const auto& [program, message] : refused) {
    std::ofstream(path) << program;
    Pipeline pipeline(xy);
    long setpoints = 0;
    PipelineEvents events;
    events.setpoint = [&](const Setpoint&) { ++setpoints; };
    try {
      (void)pipeline.run(path, events);
      FAIL() << "ran: " << program;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(message), std::string::npos) << what;
      EXPECT_NE(what.find("has no Z axis (its axes: X Y)"), std::string::npos) << what;
    }
    EXPECT_EQ(setpoints, 0);
  }
  std::ofstream(path) << "G21 G90 G17\nG0 X0 Y0 Z0\nG1 X10 F600\nG2 X10 Y0 I5 J0\nG1 Y5 Z0\nM2\n";
  Pipeline pipeline(xy);
  EXPECT_TRUE(pipeline.run(path).passed);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace kontur
