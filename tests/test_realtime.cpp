// The real-time contract: evaluation, stepping and u(s) allocate nothing (counted by replacing
// the global operator new for this test binary).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/interpolate/forward_difference.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <new>

#include "support/planner_run.hpp"
#include "support/random_curves.hpp"

namespace {
std::atomic<long> g_allocations{0};
std::atomic<long> g_frees{0};
}  // namespace

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  if (p != nullptr) g_frees.fetch_add(1, std::memory_order_relaxed);
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  if (p != nullptr) g_frees.fetch_add(1, std::memory_order_relaxed);
  std::free(p);
}

namespace kontur {
namespace {

TEST(RealTime, EvaluationSteppingInterpolationAndInverseLengthDoNotAllocate) {
  const NurbsCurve curve(testing::random_nurbs(testing::test_seed(), 3, {.min_degree = 3, .max_degree = 5}));
  const SpanPolynomialCurve spans(curve);
  const ArcLengthTable table(spans);
  ForwardDifferenceStepper plain(spans, (curve.u_max() - curve.u_min()) / 5000.0, Summation::plain);
  ForwardDifferenceStepper compensated(spans, (curve.u_max() - curve.u_min()) / 5000.0, Summation::compensated);
  // Construction is planning and may allocate (the exact mode builds its arc-length table).
  CurveInterpolator taylor1(spans, Interpolator::taylor_first_order);
  CurveInterpolator taylor2(spans, Interpolator::taylor_second_order);
  CurveInterpolator exact(spans, Interpolator::arc_length_exact);
  double sink = 0.0;
  const long before = g_allocations.load();
  for (int i = 0; i <= 1000; ++i) {
    const double u = curve.u_min() + (curve.u_max() - curve.u_min()) * i / 1000.0;
    sink += curve.derivatives(u, 3)[3].x() + spans.derivatives(u, 3)[2].y();
    sink += table.u_of_s(table.length_mm() * i / 1000.0) + table.s_of_u(u);
  }
  for (CurveInterpolator* ip : {&taylor1, &taylor2, &exact})
    while (!ip->at_end()) sink += ip->advance(table.length_mm() / 3000.0);
  while (plain.step()) sink += plain.point().x();
  while (compensated.step()) sink += compensated.point().y();
  const long after = g_allocations.load();
  EXPECT_EQ(after - before, 0) << "allocations in the per-cycle path";
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace kontur

namespace kontur {
namespace {

// The sampler neither allocates nor frees: it only marks the segments it has passed; the planner
// frees them on its next push (Trajectory::reclaim). Guarded because MotionPlanner::next() once
// freed each piece's curve and table as it popped it, which a count of `new` alone did not see.
TEST(RealTime, SamplingSetpointsNeitherAllocatesNorFrees) {
  testing::PlannerRun run(default_machine());
  // Planning (allocates): a polyline of 50 moves, all pushed and finished first.
  for (int i = 0; i < 50; ++i)
    run.planner.push(program::move_along(
        std::make_shared<LineSegment>(Vec3(i, (i % 2) * 0.5, 0), Vec3(i + 1, ((i + 1) % 2) * 0.5, 0)), 80.0, false, i));
  run.planner.finish();
  trajectory::Setpoint sp;
  long n = 0;
  const long allocations = g_allocations.load(), frees = g_frees.load();
  while (run.sampler.next(sp)) ++n;
  EXPECT_EQ(g_allocations.load() - allocations, 0) << "allocations while sampling " << n << " setpoints";
  EXPECT_EQ(g_frees.load() - frees, 0) << "frees while sampling " << n << " setpoints";
  EXPECT_TRUE(run.sampler.done());
  EXPECT_GT(n, 100);
  // What the sampler passed is freed by the planner side, not kept for ever.
  EXPECT_EQ(run.trajectory.held(), 50u);
  run.trajectory.reclaim();
  EXPECT_LE(run.trajectory.held(), 1u);
}

}  // namespace
}  // namespace kontur
