// Reading and checking G-code: blocks per second for a generated 10^6-block G1 program,
// 3D_Chips.ngc (expressions on every line) and a generated NURBS-heavy program.
// "read" = Reader::next for every block (parse, interpret, build the curve);
// "check" = kontur::gcode::check_program (read + each block's length, as `kontur check`).
#include <benchmark/benchmark.h>
#include <kontur/gcode/reader.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

std::string temp_program(const std::string& name) { return (fs::temp_directory_path() / name).string(); }

// 10^6 G1 blocks with N numbers and 3 axes, as CAM output looks.
const std::string& g1_program() {
  static const std::string path = [] {
    const std::string p = temp_program("kontur_bench_g1_1e6.ngc");
    std::FILE* f = std::fopen(p.c_str(), "w");
    std::fprintf(f, "G21 G90 G17 G94 F1200\n");
    for (int i = 0; i < 1000000; ++i)
      std::fprintf(f, "N%d G1 X%.3f Y%.3f Z%.3f\n", i + 10, (i % 1000) * 0.1, (i / 1000) * 0.05, -1.0 - (i % 7) * 0.01);
    std::fprintf(f, "M30\n");
    std::fclose(f);
    return p;
  }();
  return path;
}

// 2000 G6.2 curves of 12 control points each (rank 4), joined by G1 moves.
const std::string& nurbs_program() {
  static const std::string path = [] {
    const std::string p = temp_program("kontur_bench_nurbs.ngc");
    std::FILE* f = std::fopen(p.c_str(), "w");
    std::fprintf(f, "G21 G90 G17 F600\nG0 X0 Y0 Z0\n");
    double x = 0.0;
    for (int c = 0; c < 2000; ++c) {
      std::fprintf(f, "G6.2 P4 K0 X%.4f Y0 Z0 R1\n", x);
      for (int i = 1; i < 12; ++i) {
        const int k = i < 4 ? 0 : i - 3;
        std::fprintf(f, "K%d X%.4f Y%.4f R%.2f\n", k, x + i, (i % 2) * 3.0 + 0.1 * i, 1.0 + 0.1 * (i % 3));
      }
      for (int i = 0; i < 4; ++i) std::fprintf(f, "K9\n");
      x += 11.0;
      std::fprintf(f, "G1 X%.4f Y0\n", x);
    }
    std::fprintf(f, "M30\n");
    std::fclose(f);
    return p;
  }();
  return path;
}

const std::string chips = std::string(KONTUR_SOURCE_DIR) + "/../shared/data/gcode/3D_Chips.ngc";

void read_all(benchmark::State& state, const std::string& path) {
  long blocks = 0;
  for (auto _ : state) {
    kontur::gcode::Reader reader(path);
    kontur::gcode::Block b;
    while (reader.next(b)) ++blocks;
    benchmark::DoNotOptimize(b);
  }
  state.counters["blocks/s"] = benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate);
  state.counters["bytes/s"] = benchmark::Counter(
      static_cast<double>(fs::file_size(path)) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void check_all(benchmark::State& state, const std::string& path) {
  long blocks = 0;
  for (auto _ : state) {
    const auto s = kontur::gcode::check_program(path);
    blocks += s.blocks;
    benchmark::DoNotOptimize(s.path_length_mm);
  }
  state.counters["blocks/s"] = benchmark::Counter(static_cast<double>(blocks), benchmark::Counter::kIsRate);
}

void BM_ReadG1Million(benchmark::State& state) { read_all(state, g1_program()); }
void BM_CheckG1Million(benchmark::State& state) { check_all(state, g1_program()); }
void BM_Read3DChips(benchmark::State& state) { read_all(state, chips); }
void BM_Check3DChips(benchmark::State& state) { check_all(state, chips); }
void BM_ReadNurbsHeavy(benchmark::State& state) { read_all(state, nurbs_program()); }
void BM_CheckNurbsHeavy(benchmark::State& state) { check_all(state, nurbs_program()); }

BENCHMARK(BM_ReadG1Million)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_CheckG1Million)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Read3DChips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Check3DChips)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadNurbsHeavy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CheckNurbsHeavy)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
