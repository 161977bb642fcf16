#include <algorithm>
#include <cmath>
#include <kontur/geometry/differential.hpp>
#include <kontur/geometry/golden_section.hpp>
#include <kontur/geometry/line_segment.hpp>
#include <kontur/geometry/piece_distance.hpp>
#include <kontur/tolerances.hpp>
#include <limits>

namespace kontur {

PieceDistance::PieceDistance(const Curve& piece)
    : piece_(piece), line_(dynamic_cast<const LineSegment*>(&piece)), arc_(arc_span(piece)) {
  if (line_ != nullptr || arc_.arc != nullptr) return;
  constexpr int n = 32;
  const double a = piece.u_min(), h = (piece.u_max() - a) / n;
  for (int k = 0; k <= n; ++k) {
    u_.push_back(k == n ? piece.u_max() : a + h * k);
    points_.push_back(piece.point(u_.back()));
  }
}

double PieceDistance::operator()(const Vec3& p) const {
  if (line_ != nullptr) return segment_distance(p, line_->start(), line_->end());
  if (arc_.arc != nullptr) return arc_.arc->distance_mm(p, arc_.u0, arc_.u1);
  std::size_t best_k = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const double d = (points_[k] - p).norm();
    if (d < best) {
      best = d;
      best_k = k;
    }
  }
  const double lo = u_[best_k > 0 ? best_k - 1 : 0], hi = u_[std::min(best_k + 1, u_.size() - 1)];
  return std::min(best, golden_section_minimum([&](double u) { return (piece_.point(u) - p).norm(); }, lo, hi, 80).second);
}

double PieceDistance::lower_bound(const Vec3& p) const {
  if (line_ != nullptr) return segment_distance(p, line_->start(), line_->end());
  if (arc_.arc != nullptr) return arc_.arc->distance_lower_bound_mm(p, arc_.u0, arc_.u1);
  return 0.0;
}

double nearer_distance(const PieceDistance& a, const PieceDistance& b, const Vec3& p) {
  const double bound_a = a.lower_bound(p), bound_b = b.lower_bound(p);  // [mm]
  // (the piece of the smaller bound first; the other only where its bound does not rule it out)
  const bool a_first = bound_a <= bound_b;
  const PieceDistance& first = a_first ? a : b;
  const PieceDistance& second = a_first ? b : a;
  const double first_bound = a_first ? bound_a : bound_b, second_bound = a_first ? bound_b : bound_a;
  // (a line's bound is its distance: not computed again)
  const double d = first.bound_is_exact() ? first_bound : first(p);
  const double margin = tolerances::piece_distance_bound_margin * (1.0 + p.norm() + second_bound);  // [mm]
  if (d < second_bound - margin) return d;
  return std::min(d, second.bound_is_exact() ? second_bound : second(p));
}

}  // namespace kontur
