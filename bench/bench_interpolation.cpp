// Cost per setpoint of the interpolators along a NURBS (seed 004's Taylor updates and Kontur's
// arc-length-exact mode), on the span polynomials of the seed curve and of a 40-span cubic, at
// about 20,000 cycles per curve. items_per_second = setpoints per second.
#include <benchmark/benchmark.h>
#include <kontur/interpolation.hpp>
#include <kontur/length.hpp>
#include <kontur/span_polynomial.hpp>

#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

namespace {

using namespace kontur;

NurbsData curve_data(int which) {
  if (which == 0) return testing::seed_example(1);
  testing::RandomCurveOptions o;
  o.min_degree = o.max_degree = 3;
  o.min_points = o.max_points = 43;
  o.repeated_knots = false;
  o.offset_knots = false;
  return testing::random_nurbs(testing::test_seed(), 42, o);
}

void BM_Interpolator(benchmark::State& state, Interpolator kind, int which) {
  const NurbsCurve curve(curve_data(which));
  const SpanPolynomialCurve spans(curve);
  const double ds = length(spans) / 20000.0;
  CurveInterpolator ip(spans, kind);
  long setpoints = 0;
  for (auto _ : state) {
    ip.reset();
    Vec3 acc = Vec3::Zero();
    while (!ip.at_end()) {
      ip.advance(ds);
      acc += ip.point();
      ++setpoints;
    }
    benchmark::DoNotOptimize(acc);
  }
  state.SetItemsProcessed(setpoints);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Interpolator, taylor1_seed1, Interpolator::taylor_first_order, 0);
BENCHMARK_CAPTURE(BM_Interpolator, taylor2_seed1, Interpolator::taylor_second_order, 0);
BENCHMARK_CAPTURE(BM_Interpolator, exact_seed1, Interpolator::arc_length_exact, 0);
BENCHMARK_CAPTURE(BM_Interpolator, taylor1_cubic40, Interpolator::taylor_first_order, 1);
BENCHMARK_CAPTURE(BM_Interpolator, taylor2_cubic40, Interpolator::taylor_second_order, 1);
BENCHMARK_CAPTURE(BM_Interpolator, exact_cubic40, Interpolator::arc_length_exact, 1);

BENCHMARK_MAIN();
