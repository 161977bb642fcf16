// Per-setpoint cost of seed 002's lower level (forward differences) against direct evaluation of
// the same points: Kontur's NURBS basis-function algorithm, Horner on the span polynomials, and
// OpenCASCADE's Geom_BSplineCurve::D0. A cubic B-spline of 40 spans, 10^5 setpoints per pass.
#include <benchmark/benchmark.h>
#include <kontur/interpolate/forward_difference.hpp>
#include <kontur/geometry/nurbs.hpp>

#include "support/occt_oracle.hpp"
#include "support/random_curves.hpp"

namespace {

using namespace kontur;

constexpr long kSetpoints = 100000;

const NurbsData& cubic() {
  static const NurbsData d = [] {
    testing::RandomCurveOptions o;
    o.min_degree = o.max_degree = 3;
    o.min_points = o.max_points = 43;
    o.rational = false;
    o.repeated_knots = false;
    o.offset_knots = false;
    return testing::random_nurbs(testing::test_seed(), 42, o);
  }();
  return d;
}

void finish(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations() * kSetpoints);
  // items_per_second: setpoints per second (ns per setpoint = 1e9 / items_per_second).
}

void BM_Setpoint_ForwardDifference(benchmark::State& state, Summation sum) {
  const NurbsCurve curve(cubic());
  const SpanPolynomialCurve spans(curve);
  ForwardDifferenceStepper fd(spans, (curve.u_max() - curve.u_min()) / static_cast<double>(kSetpoints), sum);
  for (auto _ : state) {
    fd.reset();
    Vec3 acc = Vec3::Zero();
    while (fd.step()) acc += fd.point();
    benchmark::DoNotOptimize(acc);
  }
  finish(state);
}
BENCHMARK_CAPTURE(BM_Setpoint_ForwardDifference, plain, Summation::plain);
BENCHMARK_CAPTURE(BM_Setpoint_ForwardDifference, compensated, Summation::compensated);

void BM_Setpoint_DirectNurbs(benchmark::State& state) {
  const NurbsCurve curve(cubic());
  const double h = (curve.u_max() - curve.u_min()) / static_cast<double>(kSetpoints);
  for (auto _ : state) {
    Vec3 acc = Vec3::Zero();
    for (long n = 0; n < kSetpoints; ++n) acc += curve.point(curve.u_min() + static_cast<double>(n) * h);
    benchmark::DoNotOptimize(acc);
  }
  finish(state);
}
BENCHMARK(BM_Setpoint_DirectNurbs);

void BM_Setpoint_SpanPolynomialHorner(benchmark::State& state) {
  const NurbsCurve curve(cubic());
  const SpanPolynomialCurve spans(curve);
  const double h = (curve.u_max() - curve.u_min()) / static_cast<double>(kSetpoints);
  for (auto _ : state) {
    Vec3 acc = Vec3::Zero();
    for (long n = 0; n < kSetpoints; ++n) acc += spans.point(curve.u_min() + static_cast<double>(n) * h);
    benchmark::DoNotOptimize(acc);
  }
  finish(state);
}
BENCHMARK(BM_Setpoint_SpanPolynomialHorner);

void BM_Setpoint_OpenCascadeD0(benchmark::State& state) {
  const NurbsCurve curve(cubic());
  const auto occ = testing::to_occt(cubic());
  const double h = (curve.u_max() - curve.u_min()) / static_cast<double>(kSetpoints);
  for (auto _ : state) {
    double acc = 0.0;
    for (long n = 0; n < kSetpoints; ++n) {
      gp_Pnt p;
      occ->D0(curve.u_min() + static_cast<double>(n) * h, p);
      acc += p.X();
    }
    benchmark::DoNotOptimize(acc);
  }
  finish(state);
}
BENCHMARK(BM_Setpoint_OpenCascadeD0);

// The worst-case step of the stepper: a re-anchor at a span change (differences recomputed).
void BM_ForwardDifference_ReanchorWorstCase(benchmark::State& state) {
  const NurbsCurve curve(cubic());
  const SpanPolynomialCurve spans(curve);
  // A step longer than every span: each step changes span and re-anchors.
  ForwardDifferenceStepper fd(spans, (curve.u_max() - curve.u_min()) / 30.0, Summation::plain);
  for (auto _ : state) {
    fd.reset();
    Vec3 acc = Vec3::Zero();
    while (fd.step()) acc += fd.point();
    benchmark::DoNotOptimize(acc);
  }
  state.SetItemsProcessed(state.iterations() * fd.cycles());
}
BENCHMARK(BM_ForwardDifference_ReanchorWorstCase);

}  // namespace

BENCHMARK_MAIN();
