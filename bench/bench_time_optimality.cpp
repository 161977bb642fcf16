// How far the online planner is from time-optimal: for each program, the total time of
// MotionPlanner's setpoints against the acceleration-limited time-optimal reference
// (plan::time_optimal_profile, corners by the servo-period rule) on LinuxCNC's XYZ.ini machine
// with one-period jerk ramps (examples/machines/linuxcnc_xyz_acceleration_limited.toml).
// Counters: online_s, reference_s, ratio (online / reference, >= 1), reference_stop_s (corners
// as stops, the continuous-time reference), moves, the reference's grid points and grid_change
// (relative change of reference_s when the grid step is halved: its discretisation error). The program
// is read as `kontur run` reads it (feeds, rapids, G93, G61).
#include <benchmark/benchmark.h>
#include <kontur/gcode/reader.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/plan/time_optimal.hpp>
#include <kontur/program/block_moves.hpp>
#include <kontur/trajectory/sampler.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace {

using namespace kontur;

const std::string source_dir = KONTUR_SOURCE_DIR;
const std::string shared_dir = source_dir + "/../shared/data/gcode";

struct Program {
  std::vector<program::Move> moves;
};

// The program's moves as `kontur run --no-blend` plans them (dwells left out: they add the same
// time to both).
Program read_program(const std::string& path, const Machine& machine) {
  Program p;
  gcode::for_each_block(path, [&](const gcode::Block& b) {
    program::Move m = program::move_of(b, machine);
    if (m.curve) p.moves.push_back(std::move(m));
  });
  return p;
}

void BM_TimeOptimality(benchmark::State& state, const std::string& program) {
  const Machine machine = read_machine(source_dir + "/examples/machines/linuxcnc_xyz_acceleration_limited.toml");
  if (!std::filesystem::exists(program)) {
    state.SkipWithError(("missing " + program).c_str());
    return;
  }
  const Program p = read_program(program, machine);
  std::vector<plan::TimeOptimalMove> reference_moves;
  for (const auto& m : p.moves) reference_moves.push_back({m.curve.get(), m.feed_mm_s, m.exact_stop});
  double online = 0.0, reference = 0.0, reference_stop = 0.0, points = 0.0, grid_change = 0.0;
  for (auto _ : state) {
    trajectory::Trajectory trajectory;
    plan::MotionPlanner planner(machine, trajectory);
    trajectory::Sampler sampler(trajectory, machine.servo_period_s);
    trajectory::Setpoint sp, last;
    for (const auto& m : p.moves) {
      planner.push(m);
      while (sampler.next(sp)) last = sp;
    }
    planner.finish();
    while (sampler.next(sp)) last = sp;
    online = last.t_s;
    plan::TimeOptimalOptions o;
    o.corners = plan::CornerRule::servo_period;
    const plan::TimeOptimalProfile r = plan::time_optimal_profile(reference_moves, machine, o);
    reference = r.total_time_s;
    points = static_cast<double>(r.s_mm.size());
    reference_stop = plan::time_optimal_profile(reference_moves, machine).total_time_s;
    // Discretisation error: the same with half the grid step.
    o.max_step_mm /= 2;
    o.min_intervals_per_move *= 2;
    o.max_turn_rad /= 2;
    const double half = plan::time_optimal_profile(reference_moves, machine, o).total_time_s;
    grid_change = half > 0.0 ? std::abs(reference - half) / half : 0.0;
  }
  state.counters["online_s"] = online;
  state.counters["reference_s"] = reference;
  state.counters["ratio"] = reference > 0.0 ? online / reference : 1.0;
  state.counters["reference_stop_s"] = reference_stop;
  state.counters["moves"] = static_cast<double>(p.moves.size());
  state.counters["grid_points"] = points;
  state.counters["grid_change"] = grid_change;
}

void register_all() {
  const std::vector<std::string> programs = {
      source_dir + "/examples/programs/square_arc.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/arc_maxvel_xy.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/arc_time.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/basic_xy.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/full_xy.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/full_xz.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/full_yz.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/simple_arc2.ngc",
      shared_dir + "/linuxcnc-tp/arc-feed/simple_arc3.ngc",
      shared_dir + "/linuxcnc-tp/XYtests/51MeanderAve.ngc",
      shared_dir + "/linuxcnc-tp/performance/circle_small_segments_ncd.ngc",
      shared_dir + "/linuxcnc-tp/performance/random_lines_0.001in.ngc",
      shared_dir + "/linuxcnc-tp/performance/short_segments_0.001.ngc",
      shared_dir + "/3D_Chips.ngc",
      shared_dir + "/linuxcnc-nurbs/G5_butterfly-xy.ngc",
      shared_dir + "/linuxcnc-nurbs/G6_Curva_Delfino_n1-1.ngc",
      shared_dir + "/linuxcnc-nurbs/G6_Ruota_dentata_n1-1.ngc",
      shared_dir + "/linuxcnc-nurbs/G6_homer_n1-1.ngc",
  };
  for (const std::string& path : programs) {
    const std::string name = std::filesystem::path(path).stem().string();
    benchmark::RegisterBenchmark(("BM_TimeOptimality/" + name).c_str(), BM_TimeOptimality, path)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
