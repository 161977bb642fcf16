// Circle through three points (methods.md section 4; seed 001 section 2, program ARC).
#include "arc_checks.hpp"
#include "frame_matrices.hpp"

#include <kontur/geometry/circle_through_points.hpp>
#include <kontur/error.hpp>
#include <kontur/tolerances.hpp>

#include <Eigen/LU>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace kontur {

HelixArc CircleThroughPoints::curve() const { return HelixArc(frame, radius_mm, sweep_rad, 0.0); }

CircleThroughPoints circle_through_points(const Vec3& r1, const Vec3& r2, const Vec3& r3, CircleMotion motion) {
  CircleThroughPoints c;
  c.points = {r1, r2, r3};
  c.motion = motion;
  detail::check_finite(c.points);
  c.extent_mm = detail::check_distinct(c.points);

  // Seed (2.10): n = (r2 - r1) x (r3 - r1). The seed's system G r0 = h has det G = |n|^2, which
  // it compares with 0; Kontur compares |n| with the triangle's longest side squared (the
  // smallest height over the longest side), so that the verdict does not depend on the units.
  const Vec3 a = r2 - r1, b = r3 - r1, n = a.cross(b);
  const double flatness = detail::triangle_flatness(r1, r2, r3);
  if (!(flatness > tolerances::arc_collinear_relative))
    throw InputError("points-collinear",
                     fmt::format("r1 {}, r2 {} and r3 {} are collinear (smallest height / longest side = {:.3g}, must "
                                 "exceed {:g}): no circle passes through them",
                                 detail::format_point(r1), detail::format_point(r2), detail::format_point(r3), flatness,
                                 tolerances::arc_collinear_relative));

  // Seed (2.12)-(2.22): rows (r1 - r2), (r2 - r3), n and right-hand side
  // ((r1-r2).(r1+r2)/2, (r2-r3).(r2+r3)/2, n.r1). Departure: the same planes written with the
  // origin moved to r1 (rows r2 - r1, r3 - r1, n/|n|; right-hand side |r2-r1|^2/2, |r3-r1|^2/2, 0),
  // which keeps full precision when the coordinates are large compared with the circle.
  Eigen::Matrix3d G;
  G.row(0) = a.transpose();
  G.row(1) = b.transpose();
  G.row(2) = (n / n.norm()).transpose();
  const Eigen::Vector3d h(0.5 * a.squaredNorm(), 0.5 * b.squaredNorm(), 0.0);
  const Vec3 offset = G.partialPivLu().solve(h);  // r0 - r1
  c.centre = r1 + offset;
  c.radius_mm = offset.norm();

  // Relative frame (seed (2.39)-(2.46)): X towards r1, Z along n, Y = Z x X.
  c.normal = n.normalized();
  Vec3 x = -offset / c.radius_mm;
  x = (x - x.dot(c.normal) * c.normal).normalized();  // orthogonal to n to the last bit
  c.frame.centre = c.centre;
  c.frame.e1 = x;
  c.frame.normal = c.normal;
  c.frame.e2 = c.normal.cross(x);
  const detail::FrameMatrices relative = detail::frame_matrices(c.frame.e1, c.frame.e2, c.frame.normal, c.centre);
  c.to_machine = relative.to_machine;
  c.to_relative = relative.to_frame;
  for (std::size_t j = 0; j < 3; ++j) c.relative_points[j] = relative.local(c.points[j]);

  // Seed (2.52)-(2.55): 80 cases of arccos / arctan; with n oriented by the points the motion is
  // counter-clockwise about Z and one atan2 mapped to (0, 2 pi] covers them all.
  c.theta12_rad = detail::angle_in_0_2pi(std::atan2(c.relative_points[1].y(), c.relative_points[1].x()));
  c.theta13_rad = detail::angle_in_0_2pi(std::atan2(c.relative_points[2].y(), c.relative_points[2].x()));
  c.sweep_rad = motion == CircleMotion::full_circle ? 2.0 * std::numbers::pi : c.theta13_rad;
  c.length_mm = c.radius_mm * c.sweep_rad;
  return c;
}

}  // namespace kontur
