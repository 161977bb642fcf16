#pragma once
// Golden-section search for the minimum of a unimodal function on a bracket: where a curve's
// parametric speed is least (stationary points), where its curvature peaks (the planner's caps),
// the centre of an arc through a run of points (the compressor).
#include <algorithm>
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

}  // namespace kontur
