// Curve length at 1e-10 relative: Kontur's adaptive Gauss-Kronrod vs the Simpson-Runge method of
// seed 000 (both schemes) vs OpenCASCADE's GCPnts_AbscissaPoint::Length, on the seed examples and
// a seeded random set. Counters: evaluations of |C'(u)| per curve and the verified worst relative
// error against a reference (the seeds' true lengths; for the random set Kontur's Gauss-Kronrod
// at 1e-15, cross-checked against OpenCASCADE at 1e-15 when the set is built).
#include <benchmark/benchmark.h>
#include <kontur/geometry/length.hpp>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include "support/occt_oracle.hpp"
#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace {

using namespace kontur;

constexpr double kTol = 1e-10;

struct Case {
  NurbsData data;
  std::unique_ptr<NurbsCurve> curve;
  std::unique_ptr<SpanPolynomialCurve> spans;
  Handle(Geom_BSplineCurve) occ;
  double reference_mm = 0.0;
};

Case make_case(NurbsData d, double reference) {
  Case c;
  c.data = d;
  c.curve = std::make_unique<NurbsCurve>(d);
  c.spans = std::make_unique<SpanPolynomialCurve>(*c.curve);
  c.occ = testing::to_occt(d);
  c.reference_mm = reference > 0.0 ? reference : gauss_kronrod_length(*c.spans, tolerances::min_length_relative).length_mm;
  if (reference <= 0.0) {
    const double occ = testing::occt_length(c.occ, 1e-14);
    if (std::abs(occ - c.reference_mm) > 1e-11 * c.reference_mm)
      std::fprintf(stderr, "warning: reference disagreement %.3e\n", (occ - c.reference_mm) / c.reference_mm);
  }
  return c;
}

std::vector<Case>& cases(const std::string& set) {
  static std::vector<Case> seed1, seed2, random;
  if (seed1.empty()) {
    seed1.push_back(make_case(testing::seed_example(1), testing::seed_true_length_1));
    seed2.push_back(make_case(testing::seed_example(2), testing::seed_true_length_2));
    const auto n = testing::test_count(200);
    for (std::uint64_t i = 0; i < n; ++i) random.push_back(make_case(testing::random_nurbs(testing::test_seed(), i), 0.0));
  }
  if (set == "seed1") return seed1;
  if (set == "seed2") return seed2;
  return random;
}

template <class F>
void run(benchmark::State& state, const std::string& set, F&& length_of) {
  auto& cs = cases(set);
  long evals = 0;
  double worst = 0.0;
  for (auto _ : state) {
    evals = 0;
    for (const auto& c : cs) {
      long e = 0;
      const double l = length_of(c, e);
      benchmark::DoNotOptimize(l);
      evals += e;
      worst = std::max(worst, std::abs(l - c.reference_mm) / c.reference_mm);
    }
  }
  state.counters["evals_per_curve"] = static_cast<double>(evals) / static_cast<double>(cs.size());
  state.counters["worst_rel_err"] = worst;
  state.counters["us_per_curve"] = benchmark::Counter(static_cast<double>(cs.size()),
                                                      benchmark::Counter::kIsIterationInvariantRate |
                                                          benchmark::Counter::kInvert);
}

void BM_Length_Kontur_GaussKronrod(benchmark::State& state, const std::string& set) {
  run(state, set, [](const Case& c, long& e) {
    const auto r = gauss_kronrod_length(*c.spans, kTol);
    e = r.evaluations;
    return r.length_mm;
  });
}
void BM_Length_SimpsonRunge_PerSpan(benchmark::State& state, const std::string& set) {
  run(state, set, [](const Case& c, long& e) {
    const auto r = simpson_runge_length(*c.spans, SimpsonScheme::per_span, kTol);
    e = r.evaluations;
    return r.length_mm;
  });
}
void BM_Length_SimpsonRunge_WholeCurve(benchmark::State& state, const std::string& set) {
  run(state, set, [](const Case& c, long& e) {
    const auto r = simpson_runge_length(*c.spans, SimpsonScheme::whole_curve, kTol);
    e = r.evaluations;
    return r.length_mm;
  });
}
void BM_Length_OpenCascade(benchmark::State& state, const std::string& set) {
  run(state, set, [](const Case& c, long& e) {
    e = 0;  // not observable
    return testing::occt_length(c.occ, kTol);
  });
}
// Kontur's Gauss-Kronrod evaluating the NURBS by the basis-function algorithm instead of the
// span polynomials: shows what the power-basis form is worth.
void BM_Length_Kontur_GaussKronrod_DirectNurbs(benchmark::State& state, const std::string& set) {
  run(state, set, [](const Case& c, long& e) {
    const auto r = gauss_kronrod_length(*c.curve, kTol);
    e = r.evaluations;
    return r.length_mm;
  });
}

}  // namespace

#define KONTUR_LENGTH_BENCH(fn)                       \
  BENCHMARK_CAPTURE(fn, seed_example1, std::string("seed1")); \
  BENCHMARK_CAPTURE(fn, seed_example2, std::string("seed2")); \
  BENCHMARK_CAPTURE(fn, random_set, std::string("random"));

KONTUR_LENGTH_BENCH(BM_Length_Kontur_GaussKronrod)
KONTUR_LENGTH_BENCH(BM_Length_Kontur_GaussKronrod_DirectNurbs)
KONTUR_LENGTH_BENCH(BM_Length_SimpsonRunge_PerSpan)
// The whole-curve scheme only on the seed examples: on random curves with C0 knots (inner knots
// repeated degree times) Simpson's h^4 error law does not hold across the kink and Runge's rule
// runs to millions of intervals.
BENCHMARK_CAPTURE(BM_Length_SimpsonRunge_WholeCurve, seed_example1, std::string("seed1"));
BENCHMARK_CAPTURE(BM_Length_SimpsonRunge_WholeCurve, seed_example2, std::string("seed2"));
KONTUR_LENGTH_BENCH(BM_Length_OpenCascade)

BENCHMARK_MAIN();
