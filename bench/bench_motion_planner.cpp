// Cost per setpoint of the motion planner's sampling (MotionPlanner::next: profile, exact arc
// length, curve point) and of its planning per move, on a NURBS program and a polyline.
#include <benchmark/benchmark.h>
#include <kontur/line_segment.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/span_polynomial.hpp>

#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

#include <chrono>

namespace {

using namespace kontur;

std::vector<plan::MoveInput> nurbs_moves() {
  std::vector<plan::MoveInput> moves;
  const NurbsCurve c1(testing::seed_example(1));
  moves.push_back({std::make_shared<SpanPolynomialCurve>(c1), 100.0, false, 1});
  return moves;
}

std::vector<plan::MoveInput> polyline_moves() {
  std::vector<plan::MoveInput> moves;
  for (int i = 0; i < 500; ++i)
    moves.push_back({std::make_shared<LineSegment>(Vec3(i, 0.2 * (i % 3), 0), Vec3(i + 1, 0.2 * ((i + 1) % 3), 0)), 100.0,
                     false, i});
  return moves;
}

void BM_Planner(benchmark::State& state, std::vector<plan::MoveInput> (*make)()) {
  const auto moves = make();
  long setpoints = 0;
  double plan_s = 0.0, sample_s = 0.0, worst_ns = 0.0, machining_s = 0.0;
  for (auto _ : state) {
    plan::MotionPlanner p(default_machine());
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& m : moves) p.push(m);
    p.finish();
    const auto t1 = std::chrono::steady_clock::now();
    plan::Setpoint sp;
    while (true) {
      const auto a = std::chrono::steady_clock::now();
      const bool more = p.next(sp);
      const auto b = std::chrono::steady_clock::now();
      if (!more) break;
      worst_ns = std::max(worst_ns, std::chrono::duration<double, std::nano>(b - a).count());
      ++setpoints;
    }
    const auto t2 = std::chrono::steady_clock::now();
    plan_s += std::chrono::duration<double>(t1 - t0).count();
    sample_s += std::chrono::duration<double>(t2 - t1).count();
    machining_s += sp.t_s;
  }
  state.SetItemsProcessed(setpoints);
  state.counters["ns_per_setpoint"] = sample_s / static_cast<double>(setpoints) * 1e9;
  state.counters["worst_ns"] = worst_ns;  // includes the clock's own cost and the OS
  state.counters["plan_us_per_move"] = plan_s / static_cast<double>(state.iterations() * static_cast<long>(moves.size())) * 1e6;
  state.counters["x_real_time"] = machining_s / (plan_s + sample_s);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Planner, seed_nurbs, nurbs_moves)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Planner, polyline_500, polyline_moves)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
