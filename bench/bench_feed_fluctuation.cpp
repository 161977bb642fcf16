// Feed fluctuation of the interpolators (methods.md section 3): each curve is stepped from start
// to end at a constant programmed feed F (6000 mm/min) and servo period T (1 ms and 125 us), and
// the arc length of every cycle is measured (adaptive Gauss-Kronrod, independent of the
// interpolators) against F T: max_rel = max |v - F| / F, mean_rel its mean over the cycles, with
// the largest bow height of a cycle's chord [um]. Curves: the seed examples
// (examples/curves/seed_example*.json), the NURBS blocks of the LinuxCNC NURBS programs
// (../shared/data/gcode/linuxcnc-nurbs, skipped when absent; one row per program and one for all
// of them) and the ellipse, parabola and hyperbola of methods.md section 5.
// The time column is the measurement's cost, not the interpolator's (see bench_interpolation).
#include <benchmark/benchmark.h>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/io/curve_json.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include "support_programs.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace kontur;

constexpr double kFeedMmS = 6000.0 / 60.0;  // programmed feed [mm/s]
constexpr std::array<double, 2> kPeriodsS{1e-3, 125e-6};  // servo periods [s]
constexpr std::array<Interpolator, 3> kKinds{Interpolator::taylor_first_order, Interpolator::taylor_second_order,
                                              Interpolator::arc_length_exact};

using bench::CurveSet;
using bench::spans_of;

std::vector<CurveSet> curve_sets() {
  std::vector<CurveSet> sets = bench::seed_curve_sets();
  for (CurveSet& s : bench::conic_curve_sets()) sets.push_back(std::move(s));
  const std::vector<CurveSet> programs = bench::linuxcnc_nurbs_sets();
  sets.insert(sets.end(), programs.begin(), programs.end());
  CurveSet all = bench::merged_curve_set("linuxcnc_nurbs_all", programs);
  if (!all.curves.empty()) sets.push_back(std::move(all));
  return sets;
}

void BM_FeedFluctuation(benchmark::State& state, const CurveSet* set, Interpolator kind, double period_s) {
  long cycles = 0;
  double max_rel = 0.0, sum_rel = 0.0, max_chord_mm = 0.0;
  for (auto _ : state) {
    cycles = 0;
    max_rel = sum_rel = max_chord_mm = 0.0;
    for (const auto& c : set->curves) {
      const FeedFluctuation f = measure_feed_fluctuation(*c, kind, kFeedMmS, period_s);
      cycles += f.cycles;
      max_rel = std::max(max_rel, f.max_relative);
      sum_rel += f.mean_relative * static_cast<double>(f.cycles);
      max_chord_mm = std::max(max_chord_mm, f.max_chord_error_mm);
    }
  }
  state.counters["curves"] = static_cast<double>(set->curves.size());
  state.counters["cycles"] = static_cast<double>(cycles);
  state.counters["max_rel"] = max_rel;
  state.counters["mean_rel"] = cycles > 0 ? sum_rel / static_cast<double>(cycles) : 0.0;
  state.counters["max_chord_um"] = max_chord_mm * 1e3;
}

}  // namespace

int main(int argc, char** argv) {
  static const std::vector<CurveSet> sets = curve_sets();
  for (const double period : kPeriodsS)
    for (const auto& s : sets)
      for (const Interpolator kind : kKinds) {
        const std::string name = "BM_FeedFluctuation/" + s.name + "/" + to_string(kind) +
                                 "/T_us:" + std::to_string(static_cast<int>(period * 1e6 + 0.5));
        benchmark::RegisterBenchmark(name.c_str(), BM_FeedFluctuation, &s, kind, period)
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
      }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
