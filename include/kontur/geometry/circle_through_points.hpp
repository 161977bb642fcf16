#pragma once
// Circle through three points in space (methods.md section 4; seed 001, section 2 and program
// ARC): centre, radius, plane, the relative frame and its homogeneous matrices, the angles of
// the points, the arc's angle, length and direction. The arc itself is a HelixArc (rise 0), so
// that length, u(s) and the motion modes treat it like any other Curve.
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/helix_arc.hpp>

#include <Eigen/Core>

#include <array>

namespace kontur {

/// What to fit: the arc from r1 through r2 to r3, or the full circle from r1 back to r1.
enum class CircleMotion {
  arc = 1,          ///< the seed's motion type 1: from r1 through r2 to r3
  full_circle = 2,  ///< the seed's motion type 2: the whole circle, from r1 through r2, r3 to r1
};

/// The circle through r1, r2, r3 and everything the program ARC reports about it.
struct CircleThroughPoints {
  std::array<Vec3, 3> points;            ///< r1, r2, r3 in the machine frame [mm]
  CircleMotion motion = CircleMotion::arc;
  Vec3 centre = Vec3::Zero();            ///< r0 [mm]
  double radius_mm = 0.0;                ///< R [mm]
  /// Unit normal n / |n|, n = (r2 - r1) x (r3 - r1): the motion is counter-clockwise about it.
  Vec3 normal = Vec3::UnitZ();
  /// Relative frame: origin r0, X towards r1, Z along the normal, Y = Z x X.
  CircleFrame frame;
  /// T: relative -> machine homogeneous coordinates, [[R, r0], [0, 1]], R's columns X, Y, Z.
  Eigen::Matrix4d to_machine = Eigen::Matrix4d::Identity();
  /// T^-1: machine -> relative, [[R^T, -R^T r0], [0, 1]].
  Eigen::Matrix4d to_relative = Eigen::Matrix4d::Identity();
  std::array<Vec3, 3> relative_points;   ///< r1, r2, r3 in the relative frame [mm] (z = 0)
  double theta12_rad = 0.0;              ///< central angle from r1 to r2, in (0, 2 pi] [rad]
  double theta13_rad = 0.0;              ///< central angle from r1 to r3, in (0, 2 pi] [rad]
  double sweep_rad = 0.0;                ///< angle of the motion: theta13, or 2 pi for the full circle [rad]
  double length_mm = 0.0;                ///< R * sweep [mm]
  double extent_mm = 0.0;                ///< largest distance between two given points [mm]

  /// The end point of the motion: r3, or r1 for the full circle [mm].
  [[nodiscard]] const Vec3& end_point() const noexcept {
    return motion == CircleMotion::full_circle ? points[0] : points[2];
  }
  /// The arc as a Curve: a HelixArc on the relative frame, u in [0, 1], angle = sweep * u.
  [[nodiscard]] HelixArc curve() const;
};

/// Fits the circle through r1, r2, r3 [mm]. Throws InputError for a non-finite coordinate
/// ("point-finite"), coincident points ("points-coincident") or collinear points
/// ("points-collinear"), each message naming the points, the measured value and the tolerance.
[[nodiscard]] CircleThroughPoints circle_through_points(const Vec3& r1, const Vec3& r2, const Vec3& r3,
                                                        CircleMotion motion = CircleMotion::arc);

}  // namespace kontur
