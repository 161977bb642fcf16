#pragma once
// The machine's axes as every stage after planning sees them: an axis vector (one coordinate per
// axis, at most max_axes, no allocation) and its layout (the letters in order, linear [mm] or
// rotary [deg], where the tool point's X Y Z sit, and the rule a feed applies by). The tool path
// (X Y Z, what curves describe) and the extra axes (A B C U V W, ExtraAxes) are kept apart: a
// later kinematics stage (5-axis tool-centre-point) maps them to the axis vector. Today the axis
// vector is the tool point's X Y Z and the extra axes, each where the layout puts it.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <kontur/geometry/curve.hpp>
#include <string>
#include <string_view>

namespace kontur {

/// Largest number of axes (LinuxCNC's X Y Z A B C U V W).
inline constexpr int max_axes = 9;

/// One coordinate per axis, in the layout's order [mm] (linear) or [deg] (rotary). Fixed capacity,
/// dynamic size: never allocates.
using AxisVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, max_axes, 1>;

/// The axes beside the tool point's X Y Z, in this order: A B C rotary [deg], U V W linear [mm].
inline constexpr char extra_axis_letters[] = "ABCUVW";
/// Number of extra axes.
inline constexpr int extra_axis_count = 6;
/// Positions of the extra axes, in extra_axis_letters' order: A B C [deg], U V W [mm].
using ExtraAxes = std::array<double, extra_axis_count>;
/// Index of an extra axis letter in ExtraAxes (A = 0 .. W = 5), or -1 (X Y Z and others).
[[nodiscard]] constexpr int extra_axis_index(char letter) noexcept {
  for (int i = 0; i < extra_axis_count; ++i)
    if (extra_axis_letters[i] == letter) return i;
  return -1;
}

/// The extra axes a fraction `f` of the way from `from` to `to` (linear): exactly `from` at f <= 0 and
/// `to` at f >= 1.
[[nodiscard]] inline ExtraAxes extra_between(const ExtraAxes& from, const ExtraAxes& to, double f) noexcept {
  if (!(f > 0.0)) return from;
  if (f >= 1.0) return to;
  ExtraAxes x;
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = from[i] + f * (to[i] - from[i]);
  return x;
}

/// Linear axes move in [mm], rotary axes turn in [deg].
enum class AxisKind { linear, rotary };

/// What a programmed feed F is a speed of (LinuxCNC's rule: the X Y Z distance when X Y Z move,
/// else the U V W distance, else the rotary angle in [deg/min]).
enum class FeedRule { linuxcnc };

/// The axes of the setpoints, in order.
class AxisLayout {
 public:
  /// X Y Z, linear, LinuxCNC's feed rule.
  [[nodiscard]] static AxisLayout xyz();
  /// Axes by letters (each of X Y Z A B C U V W at most once; A B C rotary, the others linear);
  /// throws InputError ("axes-invalid") naming the letter otherwise.
  [[nodiscard]] static AxisLayout from_letters(std::string_view letters);

  /// Number of axes.
  [[nodiscard]] int size() const noexcept { return size_; }
  /// Letter of axis i (0 <= i < size()).
  [[nodiscard]] char letter(int i) const noexcept { return letters_[static_cast<std::size_t>(i)]; }
  /// Kind of axis i.
  [[nodiscard]] AxisKind kind(int i) const noexcept { return kinds_[static_cast<std::size_t>(i)]; }
  /// The letters in order, e.g. "XYZ".
  [[nodiscard]] std::string letters() const { return std::string(letters_.data(), static_cast<std::size_t>(size_)); }
  /// Index of the axis named `letter`, or -1.
  [[nodiscard]] int index_of(char letter) const noexcept;
  /// The feed rule.
  [[nodiscard]] FeedRule feed_rule() const noexcept { return feed_rule_; }

  /// The axis vector of a tool point: X Y Z taken from it, every other axis `rest` (0 by default).
  [[nodiscard]] AxisVector from_tool(const Vec3& p) const noexcept;
  /// The tool point X Y Z of an axis vector (an axis the layout lacks: 0).
  [[nodiscard]] Vec3 tool(const AxisVector& a) const noexcept;
  /// The axis vector of a tool point and the extra axes (an extra axis the layout lacks is dropped).
  [[nodiscard]] AxisVector from_tool(const Vec3& p, const ExtraAxes& extra) const noexcept;
  /// The extra axes of an axis vector (an axis the layout lacks: 0).
  [[nodiscard]] ExtraAxes extra(const AxisVector& a) const noexcept;
  /// True if the layout has any of A B C U V W.
  [[nodiscard]] bool has_extra() const noexcept;

  friend bool operator==(const AxisLayout&, const AxisLayout&) = default;

 private:
  std::array<char, max_axes> letters_{};
  std::array<AxisKind, max_axes> kinds_{};
  std::array<int, 3> tool_{-1, -1, -1};  // index of X, Y, Z (-1: absent)
  std::array<int, extra_axis_count> extra_{-1, -1, -1, -1, -1, -1};  // index of A .. W (-1: absent)
  int size_ = 0;
  FeedRule feed_rule_ = FeedRule::linuxcnc;
};

}  // namespace kontur
