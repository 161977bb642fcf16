#pragma once
// The working range of a machine's axes: a box in the machine frame. Points given by the user
// and every computed setpoint must lie in it (the seed's programs check 1 <= x, y, z <= 5000).
#include <kontur/geometry/curve.hpp>

#include <string>

namespace kontur {

/// Axis-aligned box of allowed coordinates in the machine frame [mm].
struct MachineLimits {
  Vec3 min_mm = Vec3::Constant(-1e300);  ///< smallest allowed x, y, z [mm]
  Vec3 max_mm = Vec3::Constant(1e300);   ///< largest allowed x, y, z [mm]

  /// True when p lies in the box (bounds included).
  [[nodiscard]] bool contains(const Vec3& p) const noexcept {
    return (p.array() >= min_mm.array()).all() && (p.array() <= max_mm.array()).all();
  }
};

/// Checks that the box is finite and not empty (min <= max on every axis); throws InputError
/// ("limits-invalid") otherwise.
void validate_limits(const MachineLimits& limits);

/// Throws InputError ("limits-outside") naming `what` (e.g. "r2" or "step 17"), the axis, the
/// value and the bound when p is outside the box.
void check_inside_limits(const MachineLimits& limits, const Vec3& p, const std::string& what);

}  // namespace kontur
