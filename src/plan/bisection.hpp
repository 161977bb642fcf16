#pragma once
// Private to kontur/plan: the bisection of the speed-profile planners (scurve.cpp,
// banded_profile.cpp) and their test of a distance against a length.

namespace kontur::plan::detail {

inline constexpr int kBisections = 200;  // bounded; stops earlier when the interval cannot shrink

// Bisection of [lo, hi] on a predicate true on a lower part and false above it: the last point
// found true and the first found false. Bounded by kBisections; stops when the interval cannot
// shrink.
struct Bracket {
  double lo, hi;
};
template <class LowerPart>
Bracket bisect(double lo, double hi, LowerPart in_lower_part) noexcept {
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (in_lower_part(mid))
      lo = mid;
    else
      hi = mid;
  }
  return {lo, hi};
}

// Distances that agree to rounding count as equal: speeds handed from one plan to the next may
// differ in the last bits, and a braking distance 1e-16 mm over the move's length must not turn
// a feasible stop into an arrival at speed.
inline bool fits(double needed, double distance) noexcept { return needed <= distance * (1.0 + 1e-12) + 1e-15; }

}  // namespace kontur::plan::detail
