#include "circle_through_three_points.hpp"

#include <kontur/error.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace kontur::gcode::detail {

HelixArc circle_through_three_points(const Vec3& r1, const Vec3& r2, const Vec3& r3) {
  const double same = tolerances::gcode_same_point_mm;
  if ((r2 - r1).norm() <= same || (r3 - r2).norm() <= same || (r3 - r1).norm() <= same)
    throw InputError("circle-coincident",
                     (r3 - r1).norm() <= same ? "start and end point coincide (a full circle needs G2/G3 with I J K)"
                                              : "two of the three points coincide");
  const Vec3 n = (r2 - r1).cross(r3 - r1);
  const double sine = n.norm() / ((r2 - r1).norm() * (r3 - r1).norm());
  if (!(sine > tolerances::gcode_collinear_sine))
    throw InputError("circle-collinear", fmt::format("start, intermediate and end point are collinear (sine of the "
                                                     "angle between the chords {:.3g}): no circle passes through them",
                                                     sine));
  Eigen::Matrix3d a;
  a.row(0) = (r1 - r2).transpose();
  a.row(1) = (r2 - r3).transpose();
  a.row(2) = n.transpose();
  const Vec3 rhs((r1 - r2).dot(r1 + r2) / 2.0, (r2 - r3).dot(r2 + r3) / 2.0, n.dot(r1));
  const Vec3 c = a.fullPivLu().solve(rhs);
  if (!c.allFinite()) throw InputError("circle-collinear", "no circle passes through the three points");
  CircleFrame f;
  f.centre = c;
  const double radius = (r1 - c).norm();
  f.e1 = (r1 - c) / radius;
  f.normal = n.normalized();
  f.e2 = f.normal.cross(f.e1);
  const Vec3 v = r3 - c;
  double sweep = std::atan2(v.dot(f.e2), v.dot(f.e1));
  if (sweep <= 0.0) sweep += 2.0 * std::numbers::pi;
  return HelixArc(f, radius, sweep);
}

}  // namespace kontur::gcode::detail
