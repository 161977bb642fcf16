#pragma once
// Internal: the coordinate frames between program and machine coordinates: nine work offsets
// (G54 .. G59.3, set by G10 L2 / L20) with an XY rotation each (G10 L2 R), and the G92 offset
// (with the copy G92.3 restores), and the programmable frame of Sinumerik's TRANS / ROT / MIRROR
// (A p + t, A invertible: rotations, mirrors, scales; identity elsewhere). machine = Rz(R) (A program + t + G92) + work
// offset, as LinuxCNC without a programmable frame. The extra axes A B C [deg] and U V W [mm] have
// a work offset, a G92 offset and the programmable frame's translation (TRANS / ATRANS) each:
// machine = program + frame translation + G92 + work offset (rotations, scales and mirrors act on
// X Y Z). Dialect-neutral; lengths in [mm].
#include <kontur/axes.hpp>
#include <kontur/geometry/curve.hpp>

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <numbers>

namespace kontur::gcode::detail {

class CoordinateFrames {
public:
  /// Work coordinate systems 1..9 (G54 = 1 ... G59.3 = 9).
  static constexpr int system_count = 9;

  CoordinateFrames() {
    for (auto& v : offset_) v.setZero();
  }

  /// The XY rotation of work system `system` (identity without one).
  [[nodiscard]] Eigen::Matrix3d rotation(int system) const {
    const double a = rotation_deg_[index(system)] * pi / 180.0;
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    if (a != 0.0) r = Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
    return r;
  }
  /// The linear part from program to machine directions in work system `system`: its XY rotation
  /// after the programmable frame's (a mirror makes its determinant negative, a scale its columns longer).
  [[nodiscard]] Eigen::Matrix3d linear(int system) const { return rotation(system) * frame_linear_; }
  /// Program point `p` in machine coordinates, in work system `system`.
  [[nodiscard]] Vec3 to_machine(const Vec3& p, int system) const {
    return rotation(system) * (frame_linear_ * p + frame_translation_ + g92_) + offset_[index(system)];
  }
  /// Machine point `m` in program coordinates, in work system `system`.
  [[nodiscard]] Vec3 to_program(const Vec3& m, int system) const {
    return frame_inverse_ * (rotation(system).transpose() * (m - offset_[index(system)]) - g92_ - frame_translation_);
  }

  // ---- the programmable frame (Sinumerik TRANS, ROT, MIRROR and ATRANS, AROT, AMIRROR)
  /// Sets the programmable frame: program point p is A p + t in the work system (A invertible).
  void set_programmable(const Eigen::Matrix3d& linear, const Vec3& translation) noexcept {
    frame_linear_ = linear;
    frame_inverse_ = linear.inverse();
    frame_translation_ = translation;
  }
  [[nodiscard]] const Eigen::Matrix3d& programmable_linear() const noexcept { return frame_linear_; }
  /// True if the programmable frame rotates, mirrors or scales (its linear part is not the identity).
  [[nodiscard]] bool programmable_linear_set() const noexcept { return !frame_linear_.isIdentity(0.0); }
  [[nodiscard]] const Vec3& programmable_translation() const noexcept { return frame_translation_; }

  // ---- G10 L2 / L20
  /// Sets the XY rotation [deg] of work system `system` (G10 L2 R).
  void set_rotation_deg(int system, double degrees) noexcept { rotation_deg_[index(system)] = degrees; }
  /// Sets one axis (0 X, 1 Y, 2 Z) of the offset of work system `system` [mm] (G10 L2).
  void set_offset(int system, int axis, double mm) noexcept { offset_[index(system)][axis] = mm; }
  /// The offset of work system `system` that gives the machine point `m` the program coordinates
  /// `p` (G10 L20), with the system's rotation and the current G92 offset.
  [[nodiscard]] Vec3 offset_placing(const Vec3& m, const Vec3& p, int system) const {
    const double ang = rotation_deg_[index(system)] * pi / 180.0;
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(ang, Vec3::UnitZ()).toRotationMatrix();
    return m - rot * (frame_linear_ * p + frame_translation_ + g92_);
  }

  // ---- G92 family
  /// G92 on one axis: the current program coordinate `current` becomes `wanted` [mm].
  void shift_g92(int axis, double current, double wanted) noexcept { g92_[axis] = current + g92_[axis] - wanted; }
  /// Keeps the G92 offset for G92.3 (after G92), of X Y Z and the extra axes.
  void save_g92() noexcept {
    g92_saved_ = g92_;
    extra_g92_saved_ = extra_g92_;
  }
  /// G92.1 (`forget_saved`) and G92.2: no G92 offset (X Y Z and the extra axes).
  void clear_g92(bool forget_saved) noexcept {
    g92_.setZero();
    extra_g92_.fill(0.0);
    if (forget_saved) {
      g92_saved_.setZero();
      extra_g92_saved_.fill(0.0);
    }
  }
  /// G92.3: the saved G92 offset again.
  void restore_g92() noexcept {
    g92_ = g92_saved_;
    extra_g92_ = extra_g92_saved_;
  }

  // ---- the extra axes A B C [deg] U V W [mm] (index as in ExtraAxes): translations only
  /// Program positions `p` of the extra axes in machine coordinates, in work system `system`.
  [[nodiscard]] ExtraAxes extra_to_machine(const ExtraAxes& p, int system) const noexcept {
    ExtraAxes m{};
    for (std::size_t i = 0; i < m.size(); ++i)
      m[i] = p[i] + extra_frame_[i] + extra_g92_[i] + extra_offset_[index(system)][i];
    return m;
  }
  /// Machine positions `m` of the extra axes in program coordinates, in work system `system`.
  [[nodiscard]] ExtraAxes extra_to_program(const ExtraAxes& m, int system) const noexcept {
    ExtraAxes p{};
    for (std::size_t i = 0; i < p.size(); ++i)
      p[i] = m[i] - extra_offset_[index(system)][i] - extra_g92_[i] - extra_frame_[i];
    return p;
  }
  /// The programmable frame's translation of the extra axes (Sinumerik TRANS / ATRANS A.. W..).
  [[nodiscard]] const ExtraAxes& programmable_extra() const noexcept { return extra_frame_; }
  void set_programmable_extra(const ExtraAxes& t) noexcept { extra_frame_ = t; }
  /// Sets extra axis `axis` (0 A .. 5 W) of the offset of work system `system` (G10 L2).
  void set_extra_offset(int system, int axis, double v) noexcept {
    extra_offset_[index(system)][static_cast<std::size_t>(axis)] = v;
  }
  /// The offset of work system `system` on extra axis `axis` that gives the machine position `m`
  /// the program coordinate `p` (G10 L20), with the current G92 offset.
  [[nodiscard]] double extra_offset_placing(int axis, double m, double p) const noexcept {
    return m - p - extra_g92_[static_cast<std::size_t>(axis)];
  }
  /// G92 on extra axis `axis`: the program coordinate `current` becomes `wanted`.
  void shift_extra_g92(int axis, double current, double wanted) noexcept {
    auto& g = extra_g92_[static_cast<std::size_t>(axis)];
    g = current + g - wanted;
  }

private:
  static constexpr double pi = std::numbers::pi;
  static std::size_t index(int system) noexcept { return static_cast<std::size_t>(system); }

  std::array<Vec3, system_count + 1> offset_{};  // [1..9] G54..G59.3 [mm]
  std::array<double, system_count + 1> rotation_deg_{};
  Vec3 g92_ = Vec3::Zero();
  Vec3 g92_saved_ = Vec3::Zero();
  std::array<ExtraAxes, system_count + 1> extra_offset_{};  // [1..9] G54..G59.3
  ExtraAxes extra_g92_{};
  ExtraAxes extra_frame_{};
  ExtraAxes extra_g92_saved_{};
  Eigen::Matrix3d frame_linear_ = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d frame_inverse_ = Eigen::Matrix3d::Identity();
  Vec3 frame_translation_ = Vec3::Zero();
};

}  // namespace kontur::gcode::detail
