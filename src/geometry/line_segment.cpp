#include <kontur/geometry/line_segment.hpp>

#include <algorithm>

namespace kontur {

Derivatives LineSegment::derivatives(double u, int order) const noexcept {
  u = std::clamp(u, 0.0, 1.0);
  Derivatives d;
  d[0] = start_ + u * (end_ - start_);
  if (order >= 1) d[1] = end_ - start_;
  return d;
}

}  // namespace kontur
