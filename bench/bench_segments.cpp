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
#include <kontur/io/setpoint_writer.hpp>
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

// The lower level over a whole stream in memory, fed record by record as it asks (as a
// controller's ring buffer would feed it).
class Cursor {
 public:
  explicit Cursor(const std::string& stream)
      : data_(reinterpret_cast<const std::uint8_t*>(stream.data())), size_(stream.size()) {
    kll_open(&s_, data_, size_);
  }
  /// The next setpoint (feeding a record first when the piece is used up); false at the end.
  bool next(kll_setpoint& sp) {
    for (;;) {
      const int r = kll_next(&s_, &sp);
      if (r == KLL_SETPOINT) return true;
      if (r != KLL_NEED_PIECE) return false;
      std::size_t size = 0;
      kll_record_size(data_ + at_, size_ - at_, &size);
      kll_feed(&s_, data_ + at_, size);
      at_ += size;
      ++fed_;
    }
  }
  [[nodiscard]] const kll_stream& state() const noexcept { return s_; }
  [[nodiscard]] long fed() const noexcept { return fed_; }

 private:
  kll_stream s_{};
  const std::uint8_t* data_;
  std::size_t size_, at_ = KLL_HEADER_SIZE;
  long fed_ = 0;
};

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
    Cursor cursor(run->stream);
    kll_setpoint sp;
    while (cursor.next(sp)) sum += sp.position[0];
    cpu_ns += bench::thread_cpu_ns() - c0;
    n += static_cast<long>(run->setpoints.size());
  }
  benchmark::DoNotOptimize(sum);
  // Per call, timed one by one (a call that feeds a record includes it).
  const auto times = bench::repeated_call_times(5, [&](std::vector<double>& ns) {
    Cursor cursor(run->stream);
    kll_setpoint sp;
    for (;;) {
      const auto a = bench::Clock::now();
      const bool more = cursor.next(sp);
      const auto b = bench::Clock::now();
      if (!more) break;
      ns.push_back(bench::ns_between(a, b));
    }
  });
  // Additions per setpoint: the state's degree times the channels, averaged over the stream.
  double additions = 0.0;
  {
    Cursor cursor(run->stream);
    kll_setpoint sp;
    while (cursor.next(sp)) additions += cursor.state().degree * cursor.state().channels;
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
      static_cast<double>(binary_setpoint_bytes(run->layout, run->setpoints.size())) / static_cast<double>(run->stream.size());
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
  std::vector<Piece> pieces;
  {
    Cursor cursor(run->stream);
    kll_setpoint sp;
    long fed = 0;
    while (cursor.next(sp)) {
      if (cursor.fed() == fed) continue;
      // A piece was fed: its polynomial from the state at its first setpoint (already stepped once).
      fed = cursor.fed();
      const kll_stream& s = cursor.state();
      Piece p;
      p.cycles = s.remaining + 1;
      p.channels = s.channels;
      for (std::uint32_t ch = 0; ch < s.channels; ++ch) {
        // The differences at the piece's first setpoint: one step back, D_k(0) = D_k(1) - D_(k+1)(0).
        std::array<double, 6> d{};
        for (int k = 0; k <= 5; ++k) d[static_cast<std::size_t>(k)] = s.d[ch][k];
        for (int k = 4; k >= 0; --k) d[static_cast<std::size_t>(k)] -= d[static_cast<std::size_t>(k + 1)];
        for (int k = 0; k <= 5; ++k)
          for (int j = 0; j <= k; ++j)
            p.c[ch][static_cast<std::size_t>(j)] += d[static_cast<std::size_t>(k)] * segments::newton_to_power[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      }
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
