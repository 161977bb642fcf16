// Seed 002 (methods.md section 1): basis polynomials, Table 2, and conversion invariants.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>
#include <kontur/geometry/nurbs.hpp>
#include <kontur/geometry/span_polynomial.hpp>

#include "support/random_curves.hpp"
#include "support/seed_curves.hpp"

namespace kontur {
namespace {

NurbsData seed_example1() { return testing::seed_example(1); }

void expect_poly(const PolyCoeffs& c, std::array<double, 4> highest_first, const char* what) {
  for (int k = 0; k <= 3; ++k) EXPECT_DOUBLE_EQ(c[static_cast<std::size_t>(3 - k)], highest_first[static_cast<std::size_t>(k)]) << what << " power " << 3 - k;
}

TEST(SpanPolynomial, SeedBasisPolynomialsSpan1) {
  const auto d = seed_example1();
  const auto N = basis_polynomials(d.knots, 3, 3, 0.0);  // span [0, 0.5): N0..N3
  expect_poly(N[0], {-8, 12, -6, 1}, "N0");
  expect_poly(N[1], {14, -18, 6, 0}, "N1");
  expect_poly(N[2], {-8, 6, 0, 0}, "N2");
  expect_poly(N[3], {2, 0, 0, 0}, "N3");
}

TEST(SpanPolynomial, SeedBasisPolynomialsSpan2) {
  const auto d = seed_example1();
  const auto N = basis_polynomials(d.knots, 3, 4, 0.0);  // span [0.5, 1]: N1..N4
  expect_poly(N[0], {-2, 6, -6, 2}, "N1");
  expect_poly(N[1], {8, -18, 12, -2}, "N2");
  expect_poly(N[2], {-14, 24, -12, 2}, "N3");
  expect_poly(N[3], {8, -12, 6, -1}, "N4");
}

TEST(SpanPolynomial, SeedTable2CoefficientsExactly) {
  const NurbsCurve curve(seed_example1());
  const SpanPolynomialCurve spans(curve);
  ASSERT_EQ(spans.spans().size(), 2u);
  expect_poly(spans.spans()[0].coefficients(0, 0.0), {-160, 360, 0, -100}, "span 1 x");
  expect_poly(spans.spans()[0].coefficients(1, 0.0), {100, -300, 360, -60}, "span 1 y");
  expect_poly(spans.spans()[1].coefficients(0, 0.0), {-720, 1200, -420, -30}, "span 2 x");
  expect_poly(spans.spans()[1].coefficients(1, 0.0), {260, -540, 480, -80}, "span 2 y");
}

// Invariant over random curves: the span polynomials reproduce the NURBS (point and three
// derivatives) everywhere, rational or not.
TEST(SpanPolynomial, MatchesNurbsEvaluationOnRandomCurves) {
  const auto seed = testing::test_seed();
  const auto count = testing::test_count(200);
  std::mt19937_64 rng(seed);
  for (std::uint64_t i = 0; i < count; ++i) {
    const NurbsCurve curve(testing::random_nurbs(seed, i));
    const SpanPolynomialCurve spans(curve);
    const double ext = curve.extent();
    const double range = curve.u_max() - curve.u_min();
    for (int s = 0; s < 20; ++s) {
      const double u = curve.u_min() + range * std::uniform_real_distribution<double>(0, 1)(rng);
      const Derivatives a = curve.derivatives(u, 3), b = spans.derivatives(u, 3);
      double scale = ext;
      for (int k = 0; k <= 3; ++k) {
        // Derivatives scale with 1/range^k; compare relative to the larger magnitude.
        const double mag = std::max({a[k].norm(), b[k].norm(), scale});
        EXPECT_LE((a[k] - b[k]).norm(), 1e-9 * mag) << testing::describe_case(seed, i) << " u=" << u << " k=" << k;
        scale /= range;
      }
    }
  }
}

// span_index tries the span it found last first (a hint): whatever the order of the calls, it
// gives the search's answer (the last span starting at or before u; the first below u_min, the
// last at and above u_max), on knots, between them, out of range and on a copy of the curve.
TEST(SpanPolynomial, SpanIndexWithItsLastSpanHintEqualsTheSearchInAnyOrder) {
  const auto seed = testing::test_seed();
  std::mt19937_64 rng(seed);
  for (std::uint64_t i = 0; i < 100; ++i) {
    const SpanPolynomialCurve spans{NurbsCurve(testing::random_nurbs(seed, i))};
    std::vector<double> starts;
    for (const SpanPolynomial& s : spans.spans()) starts.push_back(s.u_start);
    const auto expected = [&](double u) {
      const auto it = std::upper_bound(starts.begin(), starts.end(), u);
      return it == starts.begin() ? std::size_t{0} : static_cast<std::size_t>(it - starts.begin()) - 1;
    };
    std::vector<double> us = starts;
    us.push_back(spans.u_max());
    for (double b : starts) us.push_back(std::nextafter(b, -1e300));
    us.push_back(spans.u_min() - 1.0);
    us.push_back(spans.u_max() + 1.0);
    const double range = spans.u_max() - spans.u_min();
    for (int k = 0; k < 50; ++k)
      us.push_back(spans.u_min() + range * std::uniform_real_distribution<double>(0, 1)(rng));
    std::shuffle(us.begin(), us.end(), rng);
    const SpanPolynomialCurve copy = spans;
    for (double u : us) {
      EXPECT_EQ(spans.span_index(u), expected(u)) << testing::describe_case(seed, i) << " u=" << u;
      EXPECT_EQ(spans.span_index(u), expected(u)) << "again, u=" << u;  // the hint is this span now
      EXPECT_EQ(copy.span_index(u), expected(u)) << "copy, u=" << u;
    }
  }
}

TEST(SpanPolynomial, ShiftPolynomialIsExactForDyadicShift) {
  PolyCoeffs c{};
  c[0] = -30; c[1] = -420; c[2] = 1200; c[3] = -720;
  const PolyCoeffs local = shift_polynomial(c, 3, 0.5);  // in (u - 0.5)
  const PolyCoeffs back = shift_polynomial(local, 3, -0.5);
  for (int k = 0; k <= 3; ++k) EXPECT_EQ(back[static_cast<std::size_t>(k)], c[static_cast<std::size_t>(k)]);
  EXPECT_DOUBLE_EQ(evaluate_polynomial(local, 3, 0.0), evaluate_polynomial(c, 3, 0.5));
}

}  // namespace
}  // namespace kontur
