// The two levels of issue 16 (segments/segment_stream.hpp, lower_level/kontur_ll.c), on real
// programs at 1 ms and 125 us (LinuxCNC's XYZ.ini; the 125 us machine is the same with its servo
// period changed). All in one process, so the ratios compare like with like:
//
// BM_LowerLevel: kll_next per setpoint over the whole stream (records fed as they come, as a
//   controller would): ns_per_setpoint (thread CPU time, mean), ns_p50 / ns_p999 / ns_max timed
//   call by call (over each call's fastest of 5 runs; each includes one clock read, clock_p50),
//   additions_per_setpoint (channels x degree), m4_cycles_est: those additions at
//   60 cycles each (libgcc's soft double addition on a Cortex-M4F, which has no
//   double-precision FPU; an estimate, not a measurement), bytes_per_s, size_ratio (binary
//   setpoints / stream).
// BM_DirectPolynomial: the same setpoints evaluated from each piece's polynomial by Horner's
//   scheme (what the lower level avoids): ns_per_setpoint.
// BM_PlannerPerSetpoint: the planner's whole per-setpoint cost (Pipeline::run without check or
//   writing, CPU time / setpoints), the work the lower level replaces on a controller.
// BM_SegmentFit: the upper level: the writer over the planner's setpoints (held in memory),
//   x_real_time = machining time / fitting CPU time (the issue asks >= 100 on 3D_Chips).
// Programs from ../shared/data/gcode: skipped with a note when absent.
#include <benchmark/benchmark.h>
#include <kontur/error.hpp>
#include <kontur/machine.hpp>
#include <kontur/pipeline.hpp>
#include <kontur/segments/segment_stream.hpp>

#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "kontur_ll.h"
#include "support_programs.hpp"

namespace {

using namespace kontur;

struct Run {
  std::vector<trajectory::Setpoint> setpoints;
  std::string stream;
  AxisLayout layout = AxisLayout::xyz();
  double machining_s = 0.0;
  segments::SegmentStats stats;
};

Machine machine_at(double period_s) {
  Machine m = read_machine(bench::shared_path("data/gcode/linuxcnc-tp/configs/XYZ.ini").string());
  m.servo_period_s = period_s;
  return m;
}

// The planner's setpoints of a program and the stream made of them (cached per program and period).
const Run* planned(const std::string& program, double period_s) {
  static std::vector<std::pair<std::string, std::unique_ptr<Run>>> cache;
  const std::string key = program + "@" + std::to_string(period_s);
  for (const auto& [k, r] : cache)
    if (k == key) return r.get();
  auto run = std::make_unique<Run>();
  try {
    const Machine machine = machine_at(period_s);
    PipelineOptions o;
    o.check = false;
    o.derivatives = true;
    Pipeline pipeline(machine, o);
    const std::string path = bench::shared_path("data/gcode/" + program).string();
    run->layout = pipeline.prepare(path);
    segments::SegmentOptions so;
    so.bounds = segments::axis_bounds(machine, run->layout);
    std::ostringstream out;
    segments::SegmentWriter writer(out, period_s, run->layout, so);
    PipelineEvents events;
    events.setpoint = [&](const trajectory::Setpoint& s) {
      run->setpoints.push_back(s);
      writer.write(s);
    };
    run->machining_s = pipeline.run(path, events).total_time_s;
    writer.finish();
    run->stats = writer.stats();
    run->stream = out.str();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_segments: %s skipped: %s\n", program.c_str(), e.what());
    run.reset();
  }
  cache.emplace_back(key, std::move(run));
  return cache.back().second.get();
}

// Replays the whole stream with the lower level; calls f(sp) for every setpoint.
template <class F>
void replay(const std::string& stream, F&& f) {
  kll_stream s;
  const auto* data = reinterpret_cast<const std::uint8_t*>(stream.data());
  kll_open(&s, data, stream.size());
  std::size_t at = KLL_HEADER_SIZE;
  kll_setpoint sp;
  for (;;) {
    const int r = kll_next(&s, &sp);
    if (r == KLL_SETPOINT) {
      f(sp);
      continue;
    }
    if (r != KLL_NEED_PIECE) return;
    std::size_t size = 0;
    kll_record_size(data + at, stream.size() - at, &size);
    kll_feed(&s, data + at, size);
    at += size;
  }
}

void BM_LowerLevel(benchmark::State& state, const std::string& program, double period_s) {
  const Run* run = planned(program, period_s);
  if (run == nullptr || run->setpoints.empty()) {
    state.SkipWithError("program not available");
    return;
  }
  double cpu_ns = 0.0, sum = 0.0;
  long n = 0;
  for (auto _ : state) {
    const double c0 = bench::thread_cpu_ns();
    replay(run->stream, [&](const kll_setpoint& sp) { sum += sp.position[0]; });
    cpu_ns += bench::thread_cpu_ns() - c0;
    n += static_cast<long>(run->setpoints.size());
  }
  benchmark::DoNotOptimize(sum);
  // Per call, timed one by one.
  const auto times = bench::repeated_call_times(5, [&](std::vector<double>& ns) {
    kll_stream s;
    const auto* data = reinterpret_cast<const std::uint8_t*>(run->stream.data());
    kll_open(&s, data, run->stream.size());
    std::size_t at = KLL_HEADER_SIZE;
    kll_setpoint sp;
    for (;;) {
      const auto a = bench::Clock::now();
      const int r = kll_next(&s, &sp);
      const auto b = bench::Clock::now();
      if (r == KLL_SETPOINT) {
        ns.push_back(bench::ns_between(a, b));
        continue;
      }
      if (r != KLL_NEED_PIECE) break;
      std::size_t size = 0;
      kll_record_size(data + at, run->stream.size() - at, &size);
      kll_feed(&s, data + at, size);
      at += size;
    }
  });
  // Additions per setpoint: the state's degree times the channels, averaged over the stream.
  double additions = 0.0;
  {
    kll_stream s;
    const auto* data = reinterpret_cast<const std::uint8_t*>(run->stream.data());
    kll_open(&s, data, run->stream.size());
    std::size_t at = KLL_HEADER_SIZE;
    kll_setpoint sp;
    for (;;) {
      const std::uint32_t adds = s.degree * s.channels;
      const int r = kll_next(&s, &sp);
      if (r == KLL_SETPOINT) {
        additions += adds;
        continue;
      }
      if (r != KLL_NEED_PIECE) break;
      std::size_t size = 0;
      kll_record_size(data + at, run->stream.size() - at, &size);
      kll_feed(&s, data + at, size);
      at += size;
    }
  }
  const double count = static_cast<double>(run->setpoints.size());
  state.counters["ns_per_setpoint"] = cpu_ns / static_cast<double>(n);
  state.counters["ns_p50"] = times.min_of_runs.p50_ns;
  state.counters["ns_p999"] = times.min_of_runs.p999_ns;
  state.counters["ns_max"] = times.min_of_runs.max_ns;
  state.counters["clock_p50"] = bench::clock_overhead().p50_ns;
  state.counters["additions_per_setpoint"] = additions / count;
  state.counters["m4_cycles_est"] = 60.0 * additions / count;
  state.counters["setpoints"] = count;
  state.counters["pieces"] = static_cast<double>(run->stats.pieces);
  state.counters["bytes_per_s"] = static_cast<double>(run->stream.size()) / run->machining_s;
  state.counters["size_ratio"] =
      (24.0 + 8.0 * (run->layout.size() + 3) * count) / static_cast<double>(run->stream.size());
}

void BM_DirectPolynomial(benchmark::State& state, const std::string& program, double period_s) {
  const Run* run = planned(program, period_s);
  if (run == nullptr || run->setpoints.empty()) {
    state.SkipWithError("program not available");
    return;
  }
  // Each piece's polynomial in the power basis of its cycle index, from the lower level's state at
  // its first setpoint (binom(m, k) expanded), and its length.
  struct Piece {
    std::array<std::array<double, 6>, KLL_MAX_CHANNELS> c{};
    std::uint32_t cycles = 0, channels = 0;
  };
  static constexpr std::array<std::array<double, 6>, 6> newton_to_power = {{
      {1, 0, 0, 0, 0, 0},
      {0, 1, 0, 0, 0, 0},
      {0, -1.0 / 2, 1.0 / 2, 0, 0, 0},
      {0, 2.0 / 6, -3.0 / 6, 1.0 / 6, 0, 0},
      {0, -6.0 / 24, 11.0 / 24, -6.0 / 24, 1.0 / 24, 0},
      {0, 24.0 / 120, -50.0 / 120, 35.0 / 120, -10.0 / 120, 1.0 / 120},
  }};
  std::vector<Piece> pieces;
  {
    kll_stream s;
    const auto* data = reinterpret_cast<const std::uint8_t*>(run->stream.data());
    kll_open(&s, data, run->stream.size());
    std::size_t at = KLL_HEADER_SIZE;
    kll_setpoint sp;
    for (;;) {
      const int r = kll_next(&s, &sp);
      if (r == KLL_SETPOINT) continue;
      if (r != KLL_NEED_PIECE) break;
      std::size_t size = 0;
      kll_record_size(data + at, run->stream.size() - at, &size);
      kll_feed(&s, data + at, size);
      at += size;
      Piece p;
      p.cycles = s.remaining;
      p.channels = s.channels;
      for (std::uint32_t ch = 0; ch < s.channels; ++ch)
        for (int k = 0; k <= 5; ++k)
          for (int j = 0; j <= k; ++j) p.c[ch][static_cast<std::size_t>(j)] += s.d[ch][k] * newton_to_power[k][j];
      pieces.push_back(p);
    }
  }
  double cpu_ns = 0.0, sum = 0.0;
  long n = 0;
  for (auto _ : state) {
    const double c0 = bench::thread_cpu_ns();
    for (const Piece& p : pieces)
      for (std::uint32_t m = 0; m < p.cycles; ++m) {
        const double x = m;
        for (std::uint32_t ch = 0; ch < p.channels; ++ch) {
          const auto& c = p.c[ch];
          sum += ((((c[5] * x + c[4]) * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0];
        }
        ++n;
      }
    cpu_ns += bench::thread_cpu_ns() - c0;
  }
  benchmark::DoNotOptimize(sum);
  state.counters["ns_per_setpoint"] = cpu_ns / static_cast<double>(n);
}

void BM_PlannerPerSetpoint(benchmark::State& state, const std::string& program, double period_s) {
  const Run* run = planned(program, period_s);
  if (run == nullptr || run->setpoints.empty()) {
    state.SkipWithError("program not available");
    return;
  }
  PipelineOptions o;
  o.check = false;
  Pipeline pipeline(machine_at(period_s), o);
  const std::string path = bench::shared_path("data/gcode/" + program).string();
  double cpu_ns = 0.0, sum = 0.0;
  long n = 0;
  for (auto _ : state) {
    const double c0 = bench::thread_cpu_ns();
    PipelineEvents events;
    events.setpoint = [&](const trajectory::Setpoint& sp) { sum += sp.position[0]; };
    n += pipeline.run(path, events).setpoints;
    cpu_ns += bench::thread_cpu_ns() - c0;
  }
  benchmark::DoNotOptimize(sum);
  state.counters["ns_per_setpoint"] = cpu_ns / static_cast<double>(n);
}

void BM_SegmentFit(benchmark::State& state, const std::string& program, double period_s) {
  const Run* run = planned(program, period_s);
  if (run == nullptr || run->setpoints.empty()) {
    state.SkipWithError("program not available");
    return;
  }
  const Machine machine = machine_at(period_s);
  double cpu_ns = 0.0;
  long iterations = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const double c0 = bench::thread_cpu_ns();
    std::ostringstream out;
    segments::SegmentOptions so;
    so.bounds = segments::axis_bounds(machine, run->layout);
    segments::SegmentWriter writer(out, period_s, run->layout, so);
    for (const auto& s : run->setpoints) writer.write(s);
    writer.finish();
    bytes = writer.stats().bytes;
    cpu_ns += bench::thread_cpu_ns() - c0;
    ++iterations;
  }
  state.counters["fit_ms"] = cpu_ns / static_cast<double>(iterations) / 1e6;
  state.counters["machining_s"] = run->machining_s;
  state.counters["x_real_time"] = run->machining_s / (cpu_ns / static_cast<double>(iterations) / 1e9);
  state.counters["ns_per_setpoint"] = cpu_ns / static_cast<double>(iterations) / static_cast<double>(run->setpoints.size());
  state.counters["bytes"] = static_cast<double>(bytes);
}

const int registered = [] {
  const std::vector<std::string> programs = {"3D_Chips.ngc", "linuxcnc-tp/performance/3D_Chips.ngc",
                                             "linuxcnc-tp/performance/circle_small_segments_ncd.ngc",
                                             "linuxcnc-nurbs/G5_butterfly-xy.ngc"};
  for (const double period : {1e-3, 125e-6}) {
    const std::string p = period == 1e-3 ? "1ms" : "125us";
    for (const auto& program : programs) {
      const std::string name = program + "/" + p;
      benchmark::RegisterBenchmark(("BM_LowerLevel/" + name).c_str(), BM_LowerLevel, program, period)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(3);
      benchmark::RegisterBenchmark(("BM_DirectPolynomial/" + name).c_str(), BM_DirectPolynomial, program, period)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(3);
      benchmark::RegisterBenchmark(("BM_PlannerPerSetpoint/" + name).c_str(), BM_PlannerPerSetpoint, program, period)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
      benchmark::RegisterBenchmark(("BM_SegmentFit/" + name).c_str(), BM_SegmentFit, program, period)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    }
  }
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
