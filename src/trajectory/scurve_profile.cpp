#include <algorithm>

#include "first_time_covering.hpp"
#include <cstddef>
#include <kontur/trajectory/scurve_profile.hpp>

namespace kontur::trajectory {

ScurveProfile ScurveProfile::from_phases(double distance, double v0, double v1, double peak,
                                         const std::array<double, 7>& durations, double jmax) noexcept {
  ScurveProfile p;
  p.distance_ = distance;
  p.peak_ = peak;
  p.jerk_ = {jmax, 0.0, -jmax, 0.0, -jmax, 0.0, jmax};
  p.start_[0] = {0.0, v0, 0.0, 0.0};
  p.start_time_[0] = 0.0;
  for (std::size_t k = 0; k < 7; ++k) {
    const PathState& s = p.start_[k];
    const double d = durations[k], j = p.jerk_[k];
    PathState e;
    e.a = s.a + j * d;
    e.v = s.v + s.a * d + 0.5 * j * d * d;
    e.s = s.s + s.v * d + 0.5 * s.a * d * d + j * d * d * d / 6.0;
    p.start_[k + 1] = e;
    p.start_time_[k + 1] = p.start_time_[k] + d;
  }
  // The end is exact by definition: the phases cover the distance up to rounding.
  p.start_[7] = {distance, v1, 0.0, 0.0};
  return p;
}

PathState ScurveProfile::sample(double t) const noexcept {
  if (!(t > 0.0)) return start_[0];
  if (t >= start_time_[7]) return start_[7];
  int k = 0;
  while (k < 6 && t >= start_time_[static_cast<std::size_t>(k + 1)]) ++k;
  const auto kk = static_cast<std::size_t>(k);
  const double tau = t - start_time_[kk];
  const PathState& p = start_[kk];
  const double j = jerk_[kk];
  PathState out;
  out.j = j;
  out.a = p.a + j * tau;
  out.v = p.v + p.a * tau + 0.5 * j * tau * tau;
  out.s = p.s + p.v * tau + 0.5 * p.a * tau * tau + j * tau * tau * tau / 6.0;
  // Rounding must not move past the end.
  out.s = std::min(out.s, distance_);
  out.v = std::max(out.v, 0.0);
  return out;
}

double ScurveProfile::time_at(double s_mm) const noexcept { return first_time_covering(*this, s_mm); }

}  // namespace kontur::trajectory
