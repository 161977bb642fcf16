#pragma once
// Differential geometry of a curve at a point: unit tangent, curvature, and the chord
// (bow-height) error of a step, used by the feed planner and the seed 004 interpolator.
#include <algorithm>
#include <cmath>
#include <kontur/geometry/curve.hpp>
#include <vector>

namespace kontur {

/// Unit tangent C'/|C'|; zero vector where the curve is not regular (|C'| = 0).
[[nodiscard]] Vec3 unit_tangent(const Derivatives& d) noexcept;
/// Stationary points of a curve, in increasing order: the parameters where its parametric speed
/// |C'| falls to at most `relative` times its largest value on the curve (a cusp, a degenerate end
/// such as a repeated control point, a span of no length). Per span, its ends where they are such
/// points, and the minima of |C'|^2 on a grid of `samples` intervals, refined by golden section.
[[nodiscard]] std::vector<double> stationary_points(const Curve& curve, double relative, int samples);
/// The largest parametric speed |C'| [mm per parameter unit] on a grid of `samples` intervals of
/// [u0, u1] (at u1, the limit from the left).
[[nodiscard]] double peak_parametric_speed(const Curve& curve, double u0, double u1, int samples);
/// Curvature vector K = dt/ds = C''/|C'|^2 - (C'.C'') C'/|C'|^4 [1/mm] (kappa times the principal
/// normal); zero where the curve is not regular.
[[nodiscard]] Vec3 curvature_vector(const Derivatives& d) noexcept;
/// Curvature kappa = |C' x C''| / |C'|^3 [1/mm]; 0 where the curve is not regular.
[[nodiscard]] double curvature(const Derivatives& d) noexcept;
/// Chord (bow-height) error [mm] of a chord of length `step_mm` [mm] on a circle of radius
/// `radius_mm` [mm]: delta = R - sqrt(R^2 - L^2/4). A step longer than the diameter returns R.
/// An infinite radius (straight line) gives 0.
[[nodiscard]] double chord_error(double radius_mm, double step_mm) noexcept;
/// Longest chord [mm] whose bow height on radius `radius_mm` stays within `tolerance_mm`:
/// L = 2 sqrt(R^2 - (R - delta)^2). Infinite for a straight line (radius = infinity).
[[nodiscard]] double max_chord_for_error(double radius_mm, double tolerance_mm) noexcept;
/// Chord error [mm] of the step from u0 to u1 on a curve, measured as the largest distance of
/// the curve between u0 and u1 from the chord, sampled at `samples` interior points.
[[nodiscard]] double chord_error(const Curve& curve, double u0, double u1, int samples = 16) noexcept;
/// Squared distance [mm^2] from the point p to the segment [a, b] (to a when a = b): for
/// comparisons (inline: the polyline fit's check measures millions of them).
[[nodiscard]] inline double segment_distance_squared(const Vec3& p, const Vec3& a, const Vec3& b) noexcept {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - a - t * ab).squaredNorm();
}
/// Distance [mm] from the point p to the segment [a, b]: the root of segment_distance_squared.
[[nodiscard]] inline double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) noexcept {
  return std::sqrt(segment_distance_squared(p, a, b));
}
/// Distance [mm] from p to the lines first .. last (indices of lines, clamped to the polyline) of
/// the polyline through `vertices`: line i runs from vertices[i] to vertices[i + 1]. Infinite if
/// no line is in the range.
[[nodiscard]] double polyline_distance(const std::vector<Vec3>& vertices, const Vec3& p, long first,
                                       long last) noexcept;

}  // namespace kontur
