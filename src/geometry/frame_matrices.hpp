#pragma once
// The frames of the circle and the conic through points (internal): an orthonormal frame given by
// its axes and origin in machine coordinates, as homogeneous matrices both ways.
#include <kontur/geometry/curve.hpp>

#include <Eigen/Core>

namespace kontur::detail {

/// A frame with origin `origin` and the columns of `rotation` as its x', y', z' axes [mm].
struct FrameMatrices {
  Eigen::Matrix3d rotation;     ///< frame -> machine rotation (columns: the axes)
  Vec3 origin;                  ///< origin in machine coordinates [mm]
  Eigen::Matrix4d to_machine;   ///< homogeneous frame -> machine
  Eigen::Matrix4d to_frame;     ///< homogeneous machine -> frame

  /// A machine point in frame coordinates [mm].
  [[nodiscard]] Vec3 local(const Vec3& p) const { return rotation.transpose() * (p - origin); }
};

/// The frame with axes x, y, z (orthonormal, right-handed) at `origin`.
[[nodiscard]] inline FrameMatrices frame_matrices(const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& origin) {
  FrameMatrices f;
  f.rotation.col(0) = x;
  f.rotation.col(1) = y;
  f.rotation.col(2) = z;
  f.origin = origin;
  f.to_machine.setIdentity();
  f.to_machine.topLeftCorner<3, 3>() = f.rotation;
  f.to_machine.topRightCorner<3, 1>() = origin;
  f.to_frame.setIdentity();
  f.to_frame.topLeftCorner<3, 3>() = f.rotation.transpose();
  f.to_frame.topRightCorner<3, 1>() = -f.rotation.transpose() * origin;
  return f;
}

}  // namespace kontur::detail
