#pragma once
// The jerk-limited ("S-curve", double-S) velocity profile of one move along its path: from speed
// v0 to speed v1 over a distance, with speed, acceleration and jerk limits, starting and ending at
// zero acceleration. Seven phases: jerk up, constant acceleration, jerk down, cruise, and the
// mirror for braking (the profile type is the trajectory's: trajectory/scurve_profile.hpp). The peak speed is found by bisection on the distance the two velocity
// changes need (monotone in the peak), so the profile covers the distance exactly.
#include <kontur/trajectory/scurve_profile.hpp>

#include <array>

namespace kontur::plan {

/// Limits of a profile along the path.
struct PathLimits {
  double max_velocity = 0.0;      ///< [mm/s], > 0
  double max_acceleration = 0.0;  ///< [mm/s^2], > 0
  double max_jerk = 0.0;          ///< [mm/s^3], > 0
};

using trajectory::PathState;
using trajectory::ScurveProfile;

/// Duration [s] of the fastest jerk-limited change of speed between va and vb [mm/s] (from and to
/// zero acceleration).
[[nodiscard]] double velocity_change_time(double va, double vb, double max_acceleration, double max_jerk) noexcept;
/// Distance [mm] covered by that change: (va + vb) / 2 times its duration.
[[nodiscard]] double velocity_change_distance(double va, double vb, double max_acceleration, double max_jerk) noexcept;
/// The largest speed [mm/s] reachable from v_from within `distance` [mm] (by speeding up, capped at
/// limits.max_velocity); the same value is the largest speed from which one can slow down to
/// v_from within that distance. Used by the look-ahead.
[[nodiscard]] double reachable_velocity(double v_from, double distance, const PathLimits& limits) noexcept;

/// The largest speed [mm/s] (capped at limits.max_velocity) from which braking to EVERY speed in
/// [v_after, that speed] fits in `distance`. With zero acceleration at both ends the braking
/// distance is not monotone in the end speed (stopping from 88 mm/s can take less room than
/// slowing to 43 mm/s: the lower average speed wins); it peaks at an end speed of v/3 (no
/// acceleration limit reached) or a^2 / 2j. The look-ahead brakes with this bound, so that
/// assuming rest after its window is the most conservative assumption.
[[nodiscard]] double braking_velocity(double v_after, double distance, const PathLimits& limits) noexcept;

/// Plans the fastest profile (with zero acceleration at both ends) over `distance` [mm] >= 0 from
/// speed v0 to v1 [mm/s] within `limits`. Requires v0, v1 <= max_velocity and v1 reachable from
/// v0 within the distance (reachable_velocity); otherwise the end speed is lowered (or, for a
/// start too fast to brake, the distance is covered braking as hard as allowed: the caller's
/// look-ahead must prevent that, and end_velocity() tells).
[[nodiscard]] ScurveProfile plan_scurve(double distance, double v0, double v1, const PathLimits& limits);

}  // namespace kontur::plan
