#pragma once
// Private to kontur/plan: the speed-profile planners' (scurve.cpp, banded_profile.cpp) test of a
// distance against a length (they search with geometry/bracket.hpp).

#include <kontur/geometry/bracket.hpp>

namespace kontur::plan::detail {

// Distances that agree to rounding count as equal: speeds handed from one plan to the next may
// differ in the last bits, and a braking distance 1e-16 mm over the move's length must not turn
// a feasible stop into an arrival at speed.
inline double fit_margin(double distance) noexcept { return distance * (1.0 + 1e-12) + 1e-15; }
inline bool fits(double needed, double distance) noexcept { return needed <= fit_margin(distance); }
// needed - the margin: <= 0 exactly where fits() (a - b <= 0 iff a <= b for finite doubles).
inline double fit_excess(double needed, double distance) noexcept { return needed - fit_margin(distance); }

}  // namespace kontur::plan::detail
