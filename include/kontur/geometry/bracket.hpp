#pragma once
// The last point where a predicate holds and the first where it does not, on an interval where it
// holds on a lower part: by bisection to adjacent doubles, or narrowed first by regula falsi where
// the predicate is "a continuous excess <= 0". The speed planners' largest speed that fits a
// length (plan/scurve.cpp), and the time at which a motion law covers a distance
// (trajectory/path_profile.cpp).
#include <algorithm>
#include <cmath>

namespace kontur {

/// Bisection steps at most; it stops earlier when the interval cannot shrink.
inline constexpr int bisection_max_steps = 200;

/// The last point found where a predicate holds and the first found where it does not.
struct Bracket {
  double lo, hi;
};

/// Bisection of [lo, hi] on a predicate true on a lower part and false above it, until lo and hi
/// are adjacent doubles (or bisection_max_steps).
template <class LowerPart>
Bracket bisect(double lo, double hi, LowerPart in_lower_part) noexcept {
  for (int i = 0; i < bisection_max_steps; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (in_lower_part(mid))
      lo = mid;
    else
      hi = mid;
  }
  return {lo, hi};
}

/// The same bracket as bisect() on the predicate "excess(x) <= 0", for an excess that is continuous
/// and rises through 0 on [lo, hi] (excess(lo) <= 0 < excess(hi), given as e_lo and e_hi; they
/// only steer the steps): regula falsi (Illinois) narrows the interval first, a few evaluations
/// where bisection from the whole interval takes about 55; bisection then finishes it to adjacent
/// doubles. Where the predicate is monotone, the bracket is bisect()'s, bit for bit.
template <class Excess>
Bracket narrow_and_bisect(double lo, double hi, double e_lo, double e_hi, Excess excess) noexcept {
  constexpr int kSteps = 24;            // regula falsi steps at most
  constexpr double kNarrow = 1e-14;     // then bisection, below this width relative to |hi|
  int side = 0;                         // which end the last step moved (-1 lo, +1 hi)
  for (int i = 0; i < kSteps && hi - lo > kNarrow * std::max(std::abs(lo), std::abs(hi)); ++i) {
    double x = (lo * e_hi - hi * e_lo) / (e_hi - e_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double e = excess(x);
    if (e <= 0.0) {
      lo = x;
      e_lo = e;
      if (side == -1) e_hi *= 0.5;  // Illinois: the end that stays keeps being approached
      side = -1;
    } else {
      hi = x;
      e_hi = e;
      if (side == 1) e_lo *= 0.5;
      side = 1;
    }
  }
  return bisect(lo, hi, [&](double x) { return excess(x) <= 0.0; });
}

}  // namespace kontur
