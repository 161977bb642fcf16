// Cost per setpoint of the interpolators (methods.md section 3: seed 004's first- and
// second-order Taylor updates, Kontur's default arc-length-exact mode): one advance() by
// ds = F T = 0.1 mm (6000 mm/min at 1 ms) and the point on the curve, per setpoint.
// Curves: seed example 1 and 2, a 40-span cubic, the NURBS blocks of the LinuxCNC NURBS programs
// (../shared/data/gcode/linuxcnc-nurbs, skipped when absent), the conics of methods.md section 5.
// Counters:
//   ns_mean    mean cost [ns] over whole passes (no per-call clock), thread CPU time
//   ns_wall    the same in wall-clock time (higher when other processes share the cores)
//   x_taylor1  ns_mean over the Taylor first-order ns_mean on the same curves (same process)
//   ns_p50, ns_p999, ns_max   single calls timed with steady_clock (each includes one clock
//              read), over each call's fastest of 5 runs (removes preemption by other processes)
//   ns_max_raw the slowest single call seen at all (preemption included: the OS, not Kontur)
//   clock_p50  the cost of timing an empty call in this process [ns] (subtract it from ns_p50)
#include <benchmark/benchmark.h>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/io/curve_json.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include "support/random_curves.hpp"
#include "support_programs.hpp"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace kontur;

constexpr double kStepMm = 6000.0 / 60.0 * 1e-3;  // ds = F T [mm]
constexpr std::array<Interpolator, 3> kKinds{Interpolator::taylor_first_order, Interpolator::taylor_second_order,
                                              Interpolator::arc_length_exact};

using bench::CurveSet;
using bench::spans_of;

std::vector<CurveSet> curve_sets() {
  std::vector<CurveSet> sets = bench::seed_curve_sets();
  testing::RandomCurveOptions o;
  o.min_degree = o.max_degree = 3;
  o.min_points = o.max_points = 43;
  o.repeated_knots = false;
  o.offset_knots = false;
  sets.push_back({"cubic40", {spans_of(NurbsCurve(testing::random_nurbs(testing::test_seed(), 42, o)))}});
  CurveSet all = bench::merged_curve_set("linuxcnc_nurbs_all", bench::linuxcnc_nurbs_sets());
  if (!all.curves.empty()) sets.push_back(std::move(all));
  for (CurveSet& s : bench::conic_curve_sets()) sets.push_back(std::move(s));
  return sets;
}

std::map<std::string, double>& taylor1_ns() {
  static std::map<std::string, double> m;
  return m;
}

void BM_Interpolator(benchmark::State& state, const CurveSet* set, Interpolator kind) {
  std::vector<CurveInterpolator> ips;
  for (const auto& c : set->curves) ips.emplace_back(*c, kind);  // tables built here (planning)
  long setpoints = 0;
  double total_ns = 0.0, total_wall_ns = 0.0;
  for (auto _ : state) {
    const auto t0 = bench::Clock::now();
    const double c0 = bench::thread_cpu_ns();
    Vec3 acc = Vec3::Zero();
    for (auto& ip : ips) {
      ip.reset();
      while (!ip.at_end()) {
        ip.advance(kStepMm);
        acc += ip.point();
        ++setpoints;
      }
    }
    benchmark::DoNotOptimize(acc);
    total_ns += bench::thread_cpu_ns() - c0;
    total_wall_ns += bench::ns_between(t0, bench::Clock::now());
  }
  state.SetItemsProcessed(setpoints);
  // Single calls, timed one by one; five runs, each call's fastest (see repeated_call_times).
  const bench::RepeatedCallTimes r = bench::repeated_call_times(5, [&](std::vector<double>& ns) {
    for (auto& ip : ips) {
      ip.reset();
      while (!ip.at_end()) {
        const auto a = bench::Clock::now();
        ip.advance(kStepMm);
        const Vec3 p = ip.point();
        const auto b = bench::Clock::now();
        benchmark::DoNotOptimize(p);
        ns.push_back(bench::ns_between(a, b));
      }
    }
  });
  const bench::CallTimes& t = r.min_of_runs;
  const double mean = total_ns / static_cast<double>(setpoints);
  if (kind == Interpolator::taylor_first_order) taylor1_ns()[set->name] = mean;
  const auto base = taylor1_ns().find(set->name);
  state.counters["ns_mean"] = mean;
  state.counters["ns_wall"] = total_wall_ns / static_cast<double>(setpoints);
  state.counters["x_taylor1"] = base != taylor1_ns().end() ? mean / base->second : 0.0;
  state.counters["ns_p50"] = t.p50_ns;
  state.counters["ns_p999"] = t.p999_ns;
  state.counters["ns_max"] = t.max_ns;
  state.counters["ns_max_raw"] = r.raw_max_ns;
  state.counters["clock_p50"] = bench::clock_overhead().p50_ns;
}

}  // namespace

int main(int argc, char** argv) {
  static const std::vector<CurveSet> sets = curve_sets();
  for (const auto& s : sets)
    for (const Interpolator kind : kKinds) {
      const std::string name = "BM_Interpolator/" + s.name + "/" + to_string(kind);
      benchmark::RegisterBenchmark(name.c_str(), BM_Interpolator, &s, kind);
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
