#pragma once
// Golden-section search for the minimum of a unimodal function on a bracket: where a curve's
// parametric speed is least (stationary points), the centre of an arc through a run of points (the
// compressor). Brent's method (golden sections sped up by parabolic steps) where the function is
// smooth near its minimum and evaluations cost: where a curve's curvature peaks (the planner's caps).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace kontur {

/// (x, f(x)) of the least of the last two inner points of a golden-section search for a minimum of
/// `f` in [a, b] (the least of every value it met), after at most `max_iterations` steps, once the
/// bracket is down to rounding, or once a value is at most `good_enough`.
template <class F>
[[nodiscard]] std::pair<double, double> golden_section_minimum(F&& f, double a, double b, int max_iterations,
                                                               double good_enough = -std::numeric_limits<double>::infinity()) {
  constexpr double g = 0.6180339887498949;  // (sqrt(5) - 1) / 2
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < max_iterations && a < x1 && x1 < x2 && x2 < b && std::min(f1, f2) > good_enough; ++it) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    }
  }
  return f1 <= f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

/// (x, f(x)) of the least value met by Brent's method for a minimum of `f` in [a, b]: a step to the
/// vertex of the parabola through the three best points where that step lies inside the bracket
/// and is less than half the step before last, else a golden section of the larger part. Stops
/// once the bracket around the best point is within `x_tolerance` (plus rounding of x) on both
/// sides, or after `max_evaluations` evaluations of f. (R. P. Brent, Algorithms for Minimization
/// without Derivatives, 1973, ch. 5.) On a smooth minimum it converges superlinearly (11-36
/// evaluations to 1e-10 .. 1e-12 of the bracket where 60 golden sections reach 3e-13; 22 against
/// 62 on average in tests/test_golden_section.cpp); on a jagged function it falls back to golden
/// sections and is no faster than they are.
template <class F>
[[nodiscard]] std::pair<double, double> brent_minimum(F&& f, double a, double b, double x_tolerance,
                                                      int max_evaluations) {
  constexpr double c = 0.3819660112501051;  // (3 - sqrt(5)) / 2: the golden section's smaller part
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double x = a + c * (b - a);  // best point so far
  double w = x, v = x;         // the second best and the previous second best
  double fx = f(x), fw = fx, fv = fx;
  double step = 0.0, step_before = 0.0;  // the last step and the one before it
  for (int evaluations = 1; evaluations < max_evaluations; ++evaluations) {
    const double middle = 0.5 * (a + b);
    const double tol = x_tolerance + 2.0 * eps * std::abs(x);
    if (std::abs(x - middle) <= 2.0 * tol - 0.5 * (b - a)) break;
    bool parabolic = false;
    if (std::abs(step_before) > tol) {
      // vertex of the parabola through (x, fx), (w, fw), (v, fv): x + p / q
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double older = step_before;
      step_before = step;
      if (std::abs(p) < std::abs(0.5 * q * older) && p > q * (a - x) && p < q * (b - x)) {
        step = p / q;
        const double u = x + step;
        if (u - a < 2.0 * tol || b - u < 2.0 * tol) step = x < middle ? tol : -tol;
        parabolic = true;
      }
    }
    if (!parabolic) {
      step_before = x < middle ? b - x : a - x;
      step = c * step_before;
    }
    const double u = std::abs(step) >= tol ? x + step : x + (step > 0.0 ? tol : -tol);
    const double fu = f(u);
    if (fu <= fx) {
      (u < x ? b : a) = x;
      v = w;
      fv = fw;
      w = x;
      fw = fx;
      x = u;
      fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w;
        fv = fw;
        w = u;
        fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u;
        fv = fu;
      }
    }
  }
  return {x, fx};
}

/// The largest value of `f` on [a, b]: the largest of samples + 1 equally spaced values, and
/// Brent's method for a larger one between the neighbours of the largest sample (to 1e-12 of that
/// bracket, at most 60 evaluations; 60 golden sections until 2026-12-06, to 3e-13 of it, cost
/// twice the evaluations on a smooth peak): the largest distance of a blend from the programmed
/// path it replaces.
template <class F>
[[nodiscard]] double sampled_maximum(F&& f, double a, double b, int samples) {
  const int n = std::max(samples, 2);
  const double h = (b - a) / n;
  double best = -std::numeric_limits<double>::infinity();
  int best_k = 0;
  for (int k = 0; k <= n; ++k) {
    const double v = f(a + h * k);
    if (v > best) {
      best = v;
      best_k = k;
    }
  }
  const double lo = std::max(a, a + h * (best_k - 1)), hi = std::min(b, a + h * (best_k + 1));
  // (the largest value: the least of its negative)
  const double negative_peak = brent_minimum([&](double x) { return -f(x); }, lo, hi, 1e-12 * (hi - lo), 60).second;
  return std::max(best, -negative_peak);
}

}  // namespace kontur
