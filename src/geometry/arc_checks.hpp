#pragma once
// Input checks shared by the circle and the conic through points (internal).
#include <kontur/geometry/curve.hpp>

#include <cstddef>
#include <span>
#include <string>

namespace kontur::detail {

/// "r1", "r2", ... for the point of index i (0-based).
[[nodiscard]] std::string point_name(std::size_t i);
/// "(x, y, z)" with the shortest round-trip numbers.
[[nodiscard]] std::string format_point(const Vec3& p);

/// Throws InputError "point-finite" naming the point and the axis of the first non-finite coordinate.
void check_finite(std::span<const Vec3> points);
/// Largest distance between two of the points [mm]; throws InputError "points-coincident" when two
/// points are closer than tolerances::arc_coincident_relative times it (or all coincide).
[[nodiscard]] double check_distinct(std::span<const Vec3> points);
/// Flatness of the triangle (a, b, c): its smallest height over its longest side, |n| / longest^2.
[[nodiscard]] double triangle_flatness(const Vec3& a, const Vec3& b, const Vec3& c) noexcept;
/// Maps an angle [rad] to (0, 2 pi].
[[nodiscard]] double angle_in_0_2pi(double angle_rad) noexcept;

}  // namespace kontur::detail
