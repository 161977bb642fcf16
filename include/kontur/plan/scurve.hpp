#pragma once
// The jerk-limited ("S-curve", double-S) velocity profile of one move along its path: from speed
// v0 to speed v1 over a distance, with speed, acceleration and jerk limits, starting and ending at
// zero acceleration. Seven phases: jerk up, constant acceleration, jerk down, cruise, and the
// mirror for braking. The peak speed is found by bisection on the distance the two velocity
// changes need (monotone in the peak), so the profile covers the distance exactly.
#include <array>

namespace kontur::plan {

/// Limits of a profile along the path.
struct PathLimits {
  double max_velocity = 0.0;      ///< [mm/s], > 0
  double max_acceleration = 0.0;  ///< [mm/s^2], > 0
  double max_jerk = 0.0;          ///< [mm/s^3], > 0
};

/// Kinematic state on the path at one time.
struct PathState {
  double s = 0.0;  ///< distance from the move's start [mm]
  double v = 0.0;  ///< speed [mm/s]
  double a = 0.0;  ///< acceleration [mm/s^2]
  double j = 0.0;  ///< jerk [mm/s^3]
};

/// Duration [s] of the fastest jerk-limited change of speed between va and vb [mm/s] (from and to
/// zero acceleration).
[[nodiscard]] double velocity_change_time(double va, double vb, double max_acceleration, double max_jerk) noexcept;
/// Distance [mm] covered by that change: (va + vb) / 2 times its duration.
[[nodiscard]] double velocity_change_distance(double va, double vb, double max_acceleration, double max_jerk) noexcept;
/// The largest speed [mm/s] reachable from v_from within `distance` [mm] (by speeding up, capped at
/// limits.max_velocity); the same value is the largest speed from which one can slow down to
/// v_from within that distance. Used by the look-ahead.
[[nodiscard]] double reachable_velocity(double v_from, double distance, const PathLimits& limits) noexcept;

/// A planned profile. Built by plan_scurve; sample() is noexcept and allocation-free.
class ScurveProfile {
public:
  /// Total duration [s].
  [[nodiscard]] double duration() const noexcept { return start_time_[7]; }
  /// Distance [mm].
  [[nodiscard]] double distance() const noexcept { return distance_; }
  /// Speed at the start [mm/s].
  [[nodiscard]] double start_velocity() const noexcept { return start_[0].v; }
  /// Speed at the end [mm/s] (lower than asked if that was not reachable).
  [[nodiscard]] double end_velocity() const noexcept { return start_[7].v; }
  /// Peak speed [mm/s].
  [[nodiscard]] double peak_velocity() const noexcept { return peak_; }
  /// State at time t [s] (clamped to [0, duration]); at the end exactly (distance, v1, 0, 0).
  [[nodiscard]] PathState sample(double t) const noexcept;

private:
  friend ScurveProfile plan_scurve(double, double, double, const PathLimits&);
  std::array<double, 8> start_time_{};  // start of phase k, [7] = end
  std::array<PathState, 8> start_{};    // state at the start of phase k, [7] = end
  std::array<double, 7> jerk_{};        // jerk during phase k
  double distance_ = 0.0;
  double peak_ = 0.0;
};

/// Plans the fastest profile (with zero acceleration at both ends) over `distance` [mm] >= 0 from
/// speed v0 to v1 [mm/s] within `limits`. Requires v0, v1 <= max_velocity and v1 reachable from
/// v0 within the distance (reachable_velocity); otherwise the end speed is lowered (or, for a
/// start too fast to brake, the distance is covered braking as hard as allowed: the caller's
/// look-ahead must prevent that, and end_velocity() tells).
[[nodiscard]] ScurveProfile plan_scurve(double distance, double v0, double v1, const PathLimits& limits);

}  // namespace kontur::plan
