// The motion planner's cost: trajectory::Sampler::next per setpoint (the whole per-cycle path:
// profile, exact arc length, curve point) and planning per move, on synthetic moves and on the
// LinuxCNC NURBS programs (default machine, 1 ms); and whole runs of real programs through the
// library's Pipeline (what `kontur run` calls: read, blend, plan, sample; no writing), with and
// without the streaming check, against the simulated machining time.
// Programs from ../shared/data/gcode: skipped with a note when absent or not readable.
//
// BM_Planner counters (moves pushed first, then sampled):
//   ns_per_setpoint   next() mean [ns], thread CPU time, no per-call clock
//   ns_p50, ns_p999, ns_max   next() timed call by call with steady_clock (each includes one
//                     clock read, clock_p50), over each call's fastest of 5 runs (removes
//                     preemption by other processes); ns_max_raw: slowest call seen at all
//   plan_us_per_move  push() and finish() [us] per move, thread CPU time
//   x_real_time       machining time over plan + sample CPU time
// BM_WholeRun counters:
//   machining_s       simulated time of the program [s]; setpoints, moves
//   read_share        share of the run spent reading the program (one read-only pass, same process)
//   x_real_time       machining time over the run's CPU time (x_real_time_wall: over wall time)
// BM_WholeRunChecked: the same with the streaming independent check of every setpoint (kontur run
//   without writing); its run_ms against BM_WholeRun's is the check's cost.
#include <benchmark/benchmark.h>
#include <kontur/error.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/program/block_moves.hpp>
#include <kontur/trajectory/sampler.hpp>

#include "support/seed_curves.hpp"
#include "support_programs.hpp"

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace {

using namespace kontur;

std::vector<program::Move> nurbs_moves() {
  std::vector<program::Move> moves;
  const NurbsCurve c1(testing::seed_example(1));
  moves.push_back(program::move_along(std::make_shared<SpanPolynomialCurve>(c1), 100.0, false, 1));
  moves.back().id = 0;
  return moves;
}

std::vector<program::Move> polyline_moves() {
  std::vector<program::Move> moves;
  for (int i = 0; i < 500; ++i) {
    moves.push_back(program::move_along(
        std::make_shared<LineSegment>(Vec3(i, 0.2 * (i % 3), 0), Vec3(i + 1, 0.2 * ((i + 1) % 3), 0)), 100.0, false, i));
    moves.back().id = static_cast<program::MoveId>(i);
  }
  return moves;
}

// The planner, its trajectory and the sampler, wired as the pipeline wires them.
struct Planned {
  explicit Planned(const Machine& machine, const std::vector<program::Move>& moves)
      : planner(machine, trajectory), sampler(trajectory, machine.servo_period_s) {
    for (const auto& m : moves) planner.push(m);
    planner.finish();
  }
  trajectory::Trajectory trajectory;
  plan::MotionPlanner planner;
  trajectory::Sampler sampler;
};

void BM_Planner(benchmark::State& state, const std::vector<program::Move>* moves, const Machine* machine) {
  long setpoints = 0;
  double plan_ns = 0.0, sample_ns = 0.0, machining_s = 0.0;
  for (auto _ : state) {
    const double c0 = bench::thread_cpu_ns();
    Planned p(*machine, *moves);
    const double c1 = bench::thread_cpu_ns();
    trajectory::Setpoint sp;
    double acc = 0.0;
    while (p.sampler.next(sp)) {
      acc += sp.position[0];
      ++setpoints;
    }
    benchmark::DoNotOptimize(acc);
    plan_ns += c1 - c0;
    sample_ns += bench::thread_cpu_ns() - c1;
    machining_s += sp.t_s;
  }
  // Every next() timed on its own; five runs, each call's fastest (see repeated_call_times).
  const bench::RepeatedCallTimes r = bench::repeated_call_times(5, [&](std::vector<double>& ns) {
    Planned p(*machine, *moves);
    trajectory::Setpoint sp;
    while (true) {
      const auto a = bench::Clock::now();
      const bool more = p.sampler.next(sp);
      const auto b = bench::Clock::now();
      if (!more) break;
      ns.push_back(bench::ns_between(a, b));
    }
  });
  const bench::CallTimes& t = r.min_of_runs;
  state.SetItemsProcessed(setpoints);
  state.counters["moves"] = static_cast<double>(moves->size());
  state.counters["setpoints"] = static_cast<double>(setpoints / state.iterations());
  state.counters["ns_per_setpoint"] = sample_ns / static_cast<double>(setpoints);
  state.counters["ns_p50"] = t.p50_ns;
  state.counters["ns_p999"] = t.p999_ns;
  state.counters["ns_max"] = t.max_ns;
  state.counters["ns_max_raw"] = r.raw_max_ns;
  state.counters["clock_p50"] = bench::clock_overhead().p50_ns;
  state.counters["plan_us_per_move"] =
      plan_ns * 1e-3 / static_cast<double>(state.iterations() * static_cast<long>(moves->size()));
  state.counters["x_real_time"] = machining_s / ((plan_ns + sample_ns) * 1e-9);
}

// A whole program through the library's pipeline, as `kontur run` runs it, without writing the
// setpoints; `check`: with the streaming independent check of every setpoint.
void BM_WholeRun(benchmark::State& state, const std::string& program, const Machine* machine, bool check) {
  long setpoints = 0, moves = 0;
  double machining_s = 0.0, cpu_ns = 0.0, wall_ns = 0.0;
  PipelineOptions options;
  options.check = check;
  Pipeline pipeline(*machine, options);
  for (auto _ : state) {
    const auto t0 = bench::Clock::now();
    const double c0 = bench::thread_cpu_ns();
    double acc = 0.0;
    PipelineEvents events;
    events.setpoint = [&](const trajectory::Setpoint& sp) { acc += sp.position[0]; };
    const RunResult r = pipeline.run(program, events);
    benchmark::DoNotOptimize(acc);
    cpu_ns += bench::thread_cpu_ns() - c0;
    wall_ns += bench::ns_between(t0, bench::Clock::now());
    machining_s = r.total_time_s;
    setpoints = r.setpoints;
    moves = static_cast<long>(pipeline.moves().size());
  }
  // Baseline in the same process: reading alone (both passes of for_each_block).
  const double r0 = bench::thread_cpu_ns();
  long blocks = 0;
  gcode::for_each_block(program, [&](const gcode::Block&) { ++blocks; });
  const double read_ns = bench::thread_cpu_ns() - r0;
  const double n = static_cast<double>(state.iterations());
  state.counters["moves"] = static_cast<double>(moves);
  state.counters["setpoints"] = static_cast<double>(setpoints);
  state.counters["machining_s"] = machining_s;
  state.counters["run_ms"] = cpu_ns / n * 1e-6;
  state.counters["read_share"] = read_ns / (cpu_ns / n);
  state.counters["x_real_time"] = machining_s / (cpu_ns / n * 1e-9);
  state.counters["x_real_time_wall"] = machining_s / (wall_ns / n * 1e-9);
}

// Registers `make(program)` for every program it can read; notes the others on stderr.
template <class Register>
void for_readable(const std::vector<bench::fs::path>& programs, Register&& reg) {
  for (const auto& p : programs) {
    try {
      reg(p);
    } catch (const InputError& e) {
      std::fprintf(stderr, "note: %s left out: %s\n", p.filename().string().c_str(), e.what());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  static const Machine machine = default_machine();
  static const std::vector<program::Move> seed = nurbs_moves(), polyline = polyline_moves();
  benchmark::RegisterBenchmark("BM_Planner/seed_nurbs", BM_Planner, &seed, &machine)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Planner/polyline_500", BM_Planner, &polyline, &machine)
      ->Unit(benchmark::kMillisecond);

  // LinuxCNC NURBS programs, default machine.
  static std::vector<std::vector<program::Move>> nurbs_programs;
  const auto nurbs_files = bench::ngc_files(bench::shared_path("data/gcode/linuxcnc-nurbs"));
  if (nurbs_files.empty()) std::fprintf(stderr, "note: ../shared/data/gcode/linuxcnc-nurbs absent: skipped\n");
  nurbs_programs.reserve(nurbs_files.size());  // the registered pointers stay valid
  for_readable(nurbs_files, [&](const bench::fs::path& p) {
    nurbs_programs.push_back(bench::program_moves(p, machine));
    benchmark::RegisterBenchmark(("BM_Planner/" + p.stem().string()).c_str(), BM_Planner, &nurbs_programs.back(),
                                 &machine)
        ->Unit(benchmark::kMillisecond);
  });

  // Whole runs: 3D_Chips, the trajectory planner's performance programs and diagnostic/rgh.ngc (CAM
  // output of short lines and arcs: its junctions with arcs are blended) on XYZ.ini (1 ms).
  const auto ini = bench::shared_path("data/gcode/linuxcnc-tp/configs/XYZ.ini");
  static Machine xyz;
  std::vector<bench::fs::path> runs;
  std::error_code ec;
  if (bench::fs::exists(ini, ec)) {
    xyz = read_machine(ini);
    if (bench::fs::exists(bench::shared_path("data/gcode/3D_Chips.ngc"), ec))
      runs.push_back(bench::shared_path("data/gcode/3D_Chips.ngc"));
    for (const auto& p : bench::ngc_files(bench::shared_path("data/gcode/linuxcnc-tp/performance"))) runs.push_back(p);
    if (bench::fs::exists(bench::shared_path("data/gcode/linuxcnc-tp/diagnostic/rgh.ngc"), ec))
      runs.push_back(bench::shared_path("data/gcode/linuxcnc-tp/diagnostic/rgh.ngc"));
  } else {
    std::fprintf(stderr, "note: %s absent: whole runs skipped\n", ini.string().c_str());
  }
  static std::vector<std::vector<program::Move>> run_moves;
  run_moves.reserve(runs.size());
  for_readable(runs, [&](const bench::fs::path& p) {
    run_moves.push_back(bench::program_moves(p, xyz));  // unreadable programs are left out here
    benchmark::RegisterBenchmark(("BM_Planner/" + p.parent_path().filename().string() + "/" + p.stem().string()).c_str(),
                                 BM_Planner, &run_moves.back(), &xyz)
        ->Unit(benchmark::kMillisecond);
    const std::string name = p.parent_path().filename().string() + "/" + p.stem().string();
    benchmark::RegisterBenchmark(("BM_WholeRun/" + name).c_str(), BM_WholeRun, p.string(), &xyz, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_WholeRunChecked/" + name).c_str(), BM_WholeRun, p.string(), &xyz, true)
        ->Unit(benchmark::kMillisecond);
  });

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
