// Cost of the circle and conic through points (fit, classify, frames) per call, of their length
// and arc-length table (planning), and per step of each motion mode (sampling), with a sin/cos
// baseline measured in the same run. Per-step benchmarks also report the worst single step
// ("worst_ns", timed with steady_clock, which adds its own ~20 ns).
#include <benchmark/benchmark.h>
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/geometry/circle_through_points.hpp>
#include <kontur/geometry/conic_through_points.hpp>
#include <kontur/geometry/length.hpp>

#include <array>
#include <chrono>
#include <cmath>

namespace {

using kontur::Vec3;

const std::array<Vec3, 5> kEllipse{Vec3(105, 200, 300), Vec3(104, 201.08, 301.44), Vec3(103, 201.44, 301.92),
                                   Vec3(100, 201.8, 302.4), Vec3(96, 201.08, 301.44)};
const std::array<Vec3, 5> kParabola{Vec3(96, 202.4, 303.2), Vec3(98, 200.6, 300.8), Vec3(100, 200, 300),
                                    Vec3(102, 200.6, 300.8), Vec3(106, 205.4, 307.2)};
const std::array<Vec3, 5> kHyperbola{Vec3(108.5, 196.625, 295.5), Vec3(105, 198.65, 298.2), Vec3(104, 200, 300),
                                     Vec3(105, 201.35, 301.8), Vec3(108.5, 203.375, 304.5)};

const std::array<Vec3, 5>& conic_points(int which) {
  return which == 0 ? kEllipse : which == 1 ? kParabola : kHyperbola;
}
const char* conic_name(int which) { return which == 0 ? "ellipse" : which == 1 ? "parabola" : "hyperbola"; }

// ---- baseline: one sin and one cos of a changing angle, the floor of an angular step
void BM_Baseline_SinCos(benchmark::State& state) {
  double phi = 0.1, acc = 0.0;
  for (auto _ : state) {
    acc += std::sin(phi) + std::cos(phi);
    phi += 1e-3;
    benchmark::DoNotOptimize(acc);
  }
}
BENCHMARK(BM_Baseline_SinCos);

// ---- building (planning)
void BM_CircleThroughPoints(benchmark::State& state) {
  Vec3 r1(100, 200, 300), r2(200, 250, 310), r3(260, 180, 400);
  for (auto _ : state) {
    benchmark::DoNotOptimize(r1);
    auto c = kontur::circle_through_points(r1, r2, r3);
    benchmark::DoNotOptimize(c);
  }
}
BENCHMARK(BM_CircleThroughPoints);

void BM_ConicThroughPoints(benchmark::State& state) {
  auto pts = conic_points(static_cast<int>(state.range(0)));
  state.SetLabel(conic_name(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    benchmark::DoNotOptimize(pts);
    auto k = kontur::conic_through_points(pts);
    benchmark::DoNotOptimize(k);
  }
}
BENCHMARK(BM_ConicThroughPoints)->DenseRange(0, 2);

void BM_ConicArcLength(benchmark::State& state) {
  const auto k = kontur::conic_through_points(conic_points(static_cast<int>(state.range(0))));
  const kontur::ConicArc arc = k.curve();
  state.SetLabel(conic_name(static_cast<int>(state.range(0))));
  long evaluations = 0;
  for (auto _ : state) {
    const auto r = kontur::gauss_kronrod_length(arc);
    evaluations = r.evaluations;
    benchmark::DoNotOptimize(r);
  }
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK(BM_ConicArcLength)->DenseRange(0, 2);

void BM_ConicArcLengthTable(benchmark::State& state) {
  const auto k = kontur::conic_through_points(conic_points(static_cast<int>(state.range(0))));
  const kontur::ConicArc arc = k.curve();
  state.SetLabel(conic_name(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    kontur::ArcLengthTable table(arc);
    benchmark::DoNotOptimize(table);
  }
}
BENCHMARK(BM_ConicArcLengthTable)->DenseRange(0, 2);

// ---- sampling (real time): per step
template <class Sample>
void per_step(benchmark::State& state, long samples, Sample&& sample) {
  long i = 0;
  double worst = 0.0;
  long timed = 0;
  for (auto _ : state) {
    Vec3 p;
    if ((timed & 63) == 0) {  // every 64th step is timed on its own for the worst case
      const auto t0 = std::chrono::steady_clock::now();
      p = sample(i);
      const auto t1 = std::chrono::steady_clock::now();
      worst = std::max(worst, std::chrono::duration<double, std::nano>(t1 - t0).count());
    } else {
      p = sample(i);
    }
    ++timed;
    benchmark::DoNotOptimize(p);
    if (++i == samples) i = 0;
  }
  state.counters["worst_ns"] = worst;
}

void BM_CircleAngularStep(benchmark::State& state) {
  const auto c = kontur::circle_through_points({100, 200, 300}, {200, 250, 310}, {260, 180, 400});
  const kontur::HelixArc arc = c.curve();
  const auto timing = kontur::angular_timing(c.sweep_rad, c.length_mm, kontur::AngularProblem::time_given, 10.0, 100000);
  const kontur::AngularStepper stepper(arc, timing, c.end_point());
  per_step(state, stepper.samples(), [&](long i) { return stepper.sample(static_cast<int>(i)).point; });
}
BENCHMARK(BM_CircleAngularStep);

void BM_ConicAngularStep(benchmark::State& state) {
  const auto k = kontur::conic_through_points(conic_points(static_cast<int>(state.range(0))));
  const kontur::ConicArc arc = k.curve();
  state.SetLabel(conic_name(static_cast<int>(state.range(0))));
  const auto timing = kontur::angular_timing(k.theta15_rad, 1.0, kontur::AngularProblem::time_given, 10.0, 100000);
  const kontur::AngularStepper stepper(arc, timing, k.points[4]);
  per_step(state, stepper.samples(), [&](long i) { return stepper.sample(static_cast<int>(i)).point; });
}
BENCHMARK(BM_ConicAngularStep)->DenseRange(0, 2);

void BM_CircleConstantFeedStep(benchmark::State& state) {
  const auto c = kontur::circle_through_points({100, 200, 300}, {200, 250, 310}, {260, 180, 400});
  const kontur::HelixArc arc = c.curve();
  const kontur::ArcLengthTable table(arc);
  const kontur::ConstantFeedStepper feed(arc, table, c.end_point(), 6000.0, 0.0005);  // 0.05 mm per period
  per_step(state, feed.samples(), [&](long i) { return feed.sample(i).point; });
}
BENCHMARK(BM_CircleConstantFeedStep);

void BM_ConicConstantFeedStep(benchmark::State& state) {
  const auto k = kontur::conic_through_points(conic_points(static_cast<int>(state.range(0))));
  const kontur::ConicArc arc = k.curve();
  state.SetLabel(conic_name(static_cast<int>(state.range(0))));
  const kontur::ArcLengthTable table(arc);
  const kontur::ConstantFeedStepper feed(arc, table, k.points[4], 600.0, 0.0005);  // 0.005 mm per period
  per_step(state, feed.samples(), [&](long i) { return feed.sample(i).point; });
}
BENCHMARK(BM_ConicConstantFeedStep)->DenseRange(0, 2);

// The same without the planned u_k: one ArcLengthTable::u_of_s per step.
void BM_ConicConstantFeedStepOnTheFly(benchmark::State& state) {
  const auto k = kontur::conic_through_points(conic_points(static_cast<int>(state.range(0))));
  const kontur::ConicArc arc = k.curve();
  state.SetLabel(conic_name(static_cast<int>(state.range(0))));
  const kontur::ArcLengthTable table(arc);
  const kontur::ConstantFeedStepper feed(arc, table, k.points[4], 600.0, 0.0005, 100'000'000, 0);
  per_step(state, feed.samples(), [&](long i) { return feed.sample(i).point; });
}
BENCHMARK(BM_ConicConstantFeedStepOnTheFly)->DenseRange(0, 2);

// Planning of the constant-feed mode: the table and the u_k of every period (ellipse, 0.005 mm
// per period: about 2100 periods).
void BM_ConicConstantFeedPlan(benchmark::State& state) {
  const auto k = kontur::conic_through_points(kEllipse);
  const kontur::ConicArc arc = k.curve();
  long periods = 0;
  for (auto _ : state) {
    const kontur::ArcLengthTable table(arc);
    const kontur::ConstantFeedStepper feed(arc, table, k.points[4], 600.0, 0.0005);
    periods = feed.samples() - 1;
    benchmark::DoNotOptimize(feed);
  }
  state.counters["periods"] = static_cast<double>(periods);
}
BENCHMARK(BM_ConicConstantFeedPlan)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
