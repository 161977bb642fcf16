// `kontur compress` speed (issue 17: at least 10^4 input blocks per second): the whole job on the
// shared CAM programs (reading, fitting, writing, reading the written program again and checking
// it both ways), per dialect's curves, against reading the program alone (`check_program`, the
// baseline measured in the same process: compress / read is the ratio to quote).
#include <benchmark/benchmark.h>

#include <kontur/compress/compressor.hpp>
#include <kontur/gcode/reader.hpp>

#include "support_programs.hpp"

#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

void compress(benchmark::State& state, const std::string& relative, const kontur::compress::CurveKinds& kinds) {
  const fs::path p = kontur::bench::shared_path("data/gcode/" + relative);
  if (!fs::exists(p)) {
    state.SkipWithError("shared data missing");
    return;
  }
  kontur::compress::CompressOptions o;
  o.tolerance_mm = 0.01;
  o.kinds = kinds;
  o.reader.dialect = kontur::gcode::Dialect::linuxcnc;
  std::size_t blocks = 0, out = 0, in = 0;
  for (auto _ : state) {
    const kontur::compress::CompressResult r = kontur::compress::compress_program(p.string(), o);
    blocks += r.input_blocks;
    in = r.feed_blocks_in;
    out = r.feed_blocks_out;
    benchmark::DoNotOptimize(r.text.data());
  }
  state.counters["input_blocks/s"] = benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate);
  state.counters["ratio"] = out > 0 ? static_cast<double>(in) / static_cast<double>(out) : 0.0;
}

void read_only(benchmark::State& state, const std::string& relative) {
  const fs::path p = kontur::bench::shared_path("data/gcode/" + relative);
  if (!fs::exists(p)) {
    state.SkipWithError("shared data missing");
    return;
  }
  kontur::gcode::ReaderOptions o;
  o.dialect = kontur::gcode::Dialect::linuxcnc;
  long blocks = 0;
  for (auto _ : state) blocks += kontur::gcode::check_program(p.string(), o).blocks;
  state.counters["input_blocks/s"] = benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate);
}

kontur::compress::CurveKinds arcs_only() {
  kontur::compress::CurveKinds k;
  k.splines = false;
  return k;
}

const kontur::compress::CurveKinds linuxcnc = kontur::compress::default_kinds(kontur::gcode::Dialect::linuxcnc);

void BM_Read3DChips(benchmark::State& s) { read_only(s, "3D_Chips.ngc"); }
void BM_Compress3DChips(benchmark::State& s) { compress(s, "3D_Chips.ngc", linuxcnc); }
void BM_Compress3DChipsArcs(benchmark::State& s) { compress(s, "3D_Chips.ngc", arcs_only()); }
void BM_ReadPerformance3DChips(benchmark::State& s) { read_only(s, "linuxcnc-tp/performance/3D_Chips.ngc"); }
void BM_CompressPerformance3DChips(benchmark::State& s) { compress(s, "linuxcnc-tp/performance/3D_Chips.ngc", linuxcnc); }
void BM_ReadCircleSmallSegments(benchmark::State& s) { read_only(s, "linuxcnc-tp/performance/circle_small_segments_ncd.ngc"); }
void BM_CompressCircleSmallSegments(benchmark::State& s) {
  compress(s, "linuxcnc-tp/performance/circle_small_segments_ncd.ngc", linuxcnc);
}
void BM_ReadRandomLines(benchmark::State& s) { read_only(s, "linuxcnc-tp/performance/random_lines_0.001in.ngc"); }
void BM_CompressRandomLines(benchmark::State& s) { compress(s, "linuxcnc-tp/performance/random_lines_0.001in.ngc", linuxcnc); }

BENCHMARK(BM_Read3DChips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Compress3DChips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Compress3DChipsArcs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadPerformance3DChips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CompressPerformance3DChips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadCircleSmallSegments)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CompressCircleSmallSegments)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadRandomLines)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CompressRandomLines)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
