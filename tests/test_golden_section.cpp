// The one-dimensional minimisers of geometry/golden_section.hpp: golden sections and Brent's
// method, against minima known in closed form, over seeded random brackets.
#include <kontur/geometry/bracket.hpp>
#include <kontur/geometry/golden_section.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace {

using kontur::brent_minimum;
using kontur::golden_section_minimum;

// f(x) = -(curvature of the parabola y = x^2 / (2 r) at x): its peak 1 / r at x = 0, width ~ r.
double negative_parabola_curvature(double x, double r) {
  const double slope = x / r;
  return -(1.0 / r) / std::pow(1.0 + slope * slope, 1.5);
}

TEST(Minimisers, BrentFindsASmoothPeakAsExactlyAsGoldenSectionsWithHalfTheEvaluations) {
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<double> centre(-3.0, 3.0), width(0.01, 2.0), radius(1e-3, 10.0);
  long brent_evaluations = 0, golden_evaluations = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const double x0 = centre(rng), r = radius(rng);
    const double a = x0 - width(rng), b = x0 + width(rng);
    int brent_calls = 0, golden_calls = 0;
    const auto [xb, fb] = brent_minimum(
        [&](double x) {
          ++brent_calls;
          return negative_parabola_curvature(x - x0, r);
        },
        a, b, 1e-10 * (b - a), 100);
    const auto [xg, fg] = golden_section_minimum(
        [&](double x) {
          ++golden_calls;
          return negative_parabola_curvature(x - x0, r);
        },
        a, b, 60);
    // the peak's value to rounding, its place to the flatness of the peak (f'' ~ 1 / r^3)
    EXPECT_NEAR(fb, -1.0 / r, 1e-14 / r) << "trial " << trial;
    EXPECT_LE(fb, fg + 1e-15 / r) << "trial " << trial;
    EXPECT_NEAR(xb, x0, 1e-6 * r + 1e-12) << "trial " << trial;
    EXPECT_GE(xb, a);
    EXPECT_LE(xb, b);
    brent_evaluations += brent_calls;
    golden_evaluations += golden_calls;
  }
  EXPECT_LT(brent_evaluations * 2, golden_evaluations);
}

TEST(Minimisers, BrentFindsANarrowPeakBesideTheBracketsMiddle) {
  // A peak 1e-6 of the bracket wide (a large NURBS weight bends a small part of a span), off centre:
  // the parabolic steps do not see it at first; the golden sections must still close in on it.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> where(0.05, 0.95);
  for (int trial = 0; trial < 200; ++trial) {
    const double x0 = where(rng), r = 1e-6;
    int calls = 0;
    // unimodal on [0, 1]: the narrow peak on a wide, gentle slope
    const auto f = [&](double x) {
      ++calls;
      return negative_parabola_curvature(x - x0, r) + 1e-3 * std::abs(x - x0);
    };
    const auto [x, fx] = brent_minimum(f, 0.0, 1.0, 1e-10, 100);
    EXPECT_NEAR(fx, -1.0 / r, 1e-7 / r) << "trial " << trial;
    EXPECT_LE(calls, 100);
  }
}

TEST(Minimisers, BrentStaysInsideTheBracketAndStopsOnAFlatFunction) {
  int calls = 0;
  const auto [x, fx] = brent_minimum(
      [&](double) {
        ++calls;
        return 2.0;
      },
      1.0, 2.0, 1e-12, 100);
  EXPECT_EQ(fx, 2.0);
  EXPECT_GE(x, 1.0);
  EXPECT_LE(x, 2.0);
  EXPECT_LE(calls, 100);
  // a minimum at the bracket's end: found to the tolerance
  const auto [xe, fe] = brent_minimum([](double t) { return t; }, 0.0, 1.0, 1e-12, 100);
  EXPECT_LT(xe, 1e-11);
  EXPECT_EQ(fe, xe);
}

}  // namespace

// geometry/bracket.hpp: regula falsi before the bisection must end on bisection's own bracket
// (adjacent doubles around the root) for continuous rising functions, in fewer evaluations:
// cubics (motion laws), functions with a kink at the root (speed-change distances have kinks) and
// exponentials up to e^20 over the interval. (Measured: 29, 47 and 31 evaluations on average
// against bisection's 54.)
TEST(Bracket, NarrowingEndsOnBisectionsBracketInFewerEvaluations) {
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  long narrowed_evals = 0, bisect_evals = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double lo = -10.0 * U(rng), hi = 1.0 + 100.0 * U(rng);
    const double root = lo + (hi - lo) * U(rng), k = 1e-3 + 10.0 * U(rng), U01 = U(rng);
    std::function<double(double)> f;
    switch (trial % 3) {
      case 0: f = [=](double x) { return (x - root) * (1.0 + k * (x - root) * (x - root)); }; break;
      case 1: f = [=](double x) { return x < root ? (x - root) * k : (x - root) + (x - root) * (x - root); }; break;
      default: f = [=](double x) { return std::expm1(20.0 * U01 * (x - root) / (hi - lo)); }; break;
    }
    long n = 0;
    const auto counted = [&](double x) { ++n; return f(x); };
    const kontur::Bracket a = kontur::narrow_and_bisect(lo, hi, f(lo), f(hi), counted);
    narrowed_evals += n;
    n = 0;
    const kontur::Bracket b = kontur::bisect(lo, hi, [&](double x) { return counted(x) <= 0.0; });
    bisect_evals += n;
    ASSERT_EQ(a.lo, b.lo) << trial;
    ASSERT_EQ(a.hi, b.hi) << trial;
    ASSERT_LE(f(a.lo), 0.0);
    ASSERT_GT(f(a.hi), 0.0);
  }
  EXPECT_LT(4 * narrowed_evals, 3 * bisect_evals) << narrowed_evals << " against " << bisect_evals;
}
