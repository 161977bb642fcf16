#include "arc_checks.hpp"

#include <kontur/error.hpp>
#include <kontur/machine_limits.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kontur {
namespace detail {

std::string point_name(std::size_t i) { return fmt::format("r{}", i + 1); }

std::string format_point(const Vec3& p) {
  auto num = [](double v) { return v == 0.0 ? 0.0 : v; };  // no "-0"
  return fmt::format("({:.12g}, {:.12g}, {:.12g})", num(p.x()), num(p.y()), num(p.z()));
}

void check_finite(std::span<const Vec3> points) {
  static const char* axis[3] = {"x", "y", "z"};
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(points[i][k]))
        throw InputError("point-finite", fmt::format("{}.{} = {}: every coordinate must be a finite number",
                                                     point_name(i), axis[k], points[i][k]));
}

double check_distinct(std::span<const Vec3> points) {
  double extent = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) extent = std::max(extent, (points[i] - points[j]).norm());
  const double tol = tolerances::arc_coincident_relative * extent;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      const double d = (points[i] - points[j]).norm();
      if (d <= tol)
        throw InputError("points-coincident",
                         fmt::format("{} {} and {} {} coincide (distance {:.3g} mm, must exceed {:.3g} mm = {:g} x the "
                                     "extent of the points): the points must be distinct",
                                     point_name(i), format_point(points[i]), point_name(j), format_point(points[j]), d,
                                     tol, tolerances::arc_coincident_relative));
    }
  return extent;
}

double triangle_flatness(const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  if (longest == 0.0) return 0.0;
  return (b - a).cross(c - a).norm() / (longest * longest);
}

double angle_in_0_2pi(double angle_rad) noexcept {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  double a = std::fmod(angle_rad, two_pi);
  if (a <= 0.0) a += two_pi;
  return a;
}

}  // namespace detail

void validate_limits(const MachineLimits& limits) {
  static const char* axis[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(limits.min_mm[k]) || !std::isfinite(limits.max_mm[k]) || limits.min_mm[k] > limits.max_mm[k])
      throw InputError("limits-invalid", fmt::format("machine limits of {}: [{}, {}] mm must be finite with min <= max",
                                                     axis[k], limits.min_mm[k], limits.max_mm[k]));
  }
}

void check_inside_limits(const MachineLimits& limits, const Vec3& p, const std::string& what) {
  static const char* axis[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (p[k] < limits.min_mm[k])
      throw InputError("limits-outside", fmt::format("{}: {} = {} mm is below the machine limit {} mm", what, axis[k],
                                                     p[k], limits.min_mm[k]));
    if (p[k] > limits.max_mm[k])
      throw InputError("limits-outside", fmt::format("{}: {} = {} mm is above the machine limit {} mm", what, axis[k],
                                                     p[k], limits.max_mm[k]));
  }
}

}  // namespace kontur
