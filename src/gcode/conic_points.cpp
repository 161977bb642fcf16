#include "conic_points.hpp"

#include <kontur/error.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kontur::gcode::detail {

void check_conic_points(const std::array<Vec3, 5>& p) {
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j)
      if ((p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(j)]).norm() <= tolerances::gcode_same_point_mm)
        throw InputError("conic-coincident", fmt::format("points P{} and P{} coincide (P0 = start, P1..P3 = I1= J1= K1= "
                                                         ".. I3= J3= K3=, P4 = end); a conic needs five distinct points",
                                                         i, j));
  double extent = 0.0;
  for (const auto& a : p)
    for (const auto& b : p) extent = std::max(extent, (a - b).norm());
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j)
      for (int k = j + 1; k < 5; ++k) {
        const Vec3 a = p[static_cast<std::size_t>(j)] - p[static_cast<std::size_t>(i)];
        const Vec3 b = p[static_cast<std::size_t>(k)] - p[static_cast<std::size_t>(i)];
        if (!(a.cross(b).norm() > tolerances::gcode_collinear_sine * a.norm() * b.norm()))
          throw InputError("conic-collinear", fmt::format("points P{}, P{} and P{} are collinear: the conic through the "
                                                          "five points degenerates into a pair of lines",
                                                          i, j, k));
      }
  // Plane through the three points that span the largest triangle.
  Vec3 best = Vec3::Zero();
  for (int j = 1; j < 5; ++j)
    for (int k = j + 1; k < 5; ++k) {
      const Vec3 n = (p[static_cast<std::size_t>(j)] - p[0]).cross(p[static_cast<std::size_t>(k)] - p[0]);
      if (n.norm() > best.norm()) best = n;
    }
  const Vec3 n = best.normalized();
  for (int i = 1; i < 5; ++i) {
    const double d = std::abs((p[static_cast<std::size_t>(i)] - p[0]).dot(n));
    if (d > tolerances::gcode_conic_coplanar_relative * extent)
      throw InputError("conic-not-planar", fmt::format("point P{} is {:.6g} mm off the plane of the others: the five "
                                                       "points of a conic must lie in one plane",
                                                       i, d));
  }
}

}  // namespace kontur::gcode::detail
