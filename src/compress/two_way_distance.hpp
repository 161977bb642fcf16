#pragma once
// Internal to `kontur compress`: the two-way distance between a curve (sampled) and the programmed
// lines it replaces, as the fit measures a conic and the check measures every written piece.
//
// NearestOnPolyline: the distance of points from a polyline when the points come in order along
// it (a curve sampled from start to end, the vertices of a run): each query searches the segments
// around the last nearest one, onwards while the nearest keeps moving forward, and the whole
// polyline when that finds nothing within `near_mm`, so that a distance it reports above
// `near_mm` is the true one.
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/differential.hpp>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace kontur::compress::detail {

class NearestOnPolyline {
 public:
  /// `points`: the polyline's vertices (at least one) [mm]; `near_mm`: below this a local answer is kept.
  NearestOnPolyline(std::span<const Vec3> points, double near_mm) : p_(points), near_(near_mm) {}

  /// Distance of `q` from the polyline [mm].
  double distance(const Vec3& q) {
    if (p_.size() == 1) return (q - p_[0]).norm();
    const std::size_t segments = p_.size() - 1;
    std::size_t hi = std::min(segments, cursor_ + window + 1), at = cursor_;
    double best = search(q, cursor_ > window ? cursor_ - window : 0, hi, at);
    while (hi < segments && at + window >= hi) {  // the nearest is at the window's front: go on
      const std::size_t next = std::min(segments, hi + window);
      std::size_t there = at;
      const double d = search(q, hi, next, there);
      if (d < best) {
        best = d;
        at = there;
      }
      hi = next;
    }
    if (best > near_) best = search(q, 0, segments, at);
    cursor_ = at;
    return best;
  }

 private:
  static constexpr std::size_t window = 48;
  // The distance to the nearest segment of lo .. hi - 1, and which it is (`at`).
  double search(const Vec3& q, std::size_t lo, std::size_t hi, std::size_t& at) const {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = lo; i < hi; ++i) {
      const double d = segment_distance(q, p_[i], p_[i + 1]);
      if (d < best) {
        best = d;
        at = i;
      }
    }
    return best;
  }
  std::span<const Vec3> p_;
  double near_;
  std::size_t cursor_ = 0;
};

/// The largest of: every sample's distance from the lines, every line vertex's distance from the
/// samples' polyline [mm] (exact above `near_mm`).
inline double two_way_distance(std::span<const Vec3> lines, std::span<const Vec3> samples, double near_mm) {
  NearestOnPolyline to_lines(lines, near_mm), to_curve(samples, near_mm);
  double worst = 0.0;
  for (const Vec3& q : samples) worst = std::max(worst, to_lines.distance(q));
  for (const Vec3& p : lines) worst = std::max(worst, to_curve.distance(p));
  return worst;
}

/// Appends `count` points of `c` at equal steps of its parameter, after its start, to `out`.
inline void append_samples(const Curve& c, std::size_t count, std::vector<Vec3>& out) {
  for (std::size_t k = 1; k <= count; ++k)
    out.push_back(c.point(c.u_min() + (c.u_max() - c.u_min()) * static_cast<double>(k) / static_cast<double>(count)));
}

}  // namespace kontur::compress::detail
