#pragma once
// The distance from a point to a short piece of the programmed path that a blend replaces: how
// the corner blender sizes a blend (geometry/transition_curve.hpp) and how the checker measures it
// (verify::blend_deviation), each with its own sampling of the blend.
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/helix_arc.hpp>
#include <vector>

namespace kontur {

class LineSegment;

/// A piece to measure distances to: a line exactly (segment_distance), an arc or a piece of one
/// by HelixArc::distance_mm (exact on a circle), another curve from the nearest of 33 of its
/// points, refined by a golden-section search between that point's neighbours (an upper bound:
/// never nearer than the curve).
class PieceDistance {
 public:
  /// `piece` is kept by reference.
  explicit PieceDistance(const Curve& piece);
  /// Distance [mm] from p to the piece.
  [[nodiscard]] double operator()(const Vec3& p) const;
  /// A lower bound [mm] of that distance, cheaper than it: a line's distance itself, an arc's
  /// HelixArc::distance_lower_bound_mm, 0 for another curve.
  [[nodiscard]] double lower_bound(const Vec3& p) const;
  /// The lower bound is the distance itself (a line).
  [[nodiscard]] bool bound_is_exact() const noexcept { return line_ != nullptr; }

 private:
  const Curve& piece_;
  const LineSegment* line_;
  ArcSpan arc_;
  std::vector<double> u_;   // the sampled parameters of another curve
  std::vector<Vec3> points_;
};

/// p's distance [mm] from the nearer of two pieces: exactly std::min(a(p), b(p)), the farther
/// piece's distance left out where its lower bound already exceeds the nearer's (by
/// tolerances::piece_distance_bound_margin, beyond rounding). What the corner blender sizes a blend
/// by and the checker measures it by: the two pieces a blend replaces, each point near one of them.
[[nodiscard]] double nearer_distance(const PieceDistance& a, const PieceDistance& b, const Vec3& p);

}  // namespace kontur
