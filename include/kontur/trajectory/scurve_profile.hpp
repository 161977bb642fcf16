#pragma once
// The motion law of one time segment along its piece of path: a jerk-limited ("S-curve") profile
// s(t) in seven phases (jerk up, constant acceleration, jerk down, cruise, and the mirror for
// braking), starting and ending at zero acceleration. Planned by plan::plan_scurve; sampled here.
#include <array>

namespace kontur::trajectory {

/// Kinematic state on the path at one time.
struct PathState {
  double s = 0.0;  ///< distance from the piece's start [mm]
  double v = 0.0;  ///< speed [mm/s]
  double a = 0.0;  ///< acceleration [mm/s^2]
  double j = 0.0;  ///< jerk [mm/s^3]
};

/// A planned profile. sample() is noexcept and allocation-free.
class ScurveProfile {
 public:
  /// The profile from v0 [mm/s] over `distance` [mm] to v1 with peak speed `peak` [mm/s]: the
  /// seven phases' durations [s] with jerk +j, 0, -j, 0 (cruise), -j, 0, +j [mm/s^3]. The end
  /// state is exact (distance, v1, 0, 0) by definition.
  [[nodiscard]] static ScurveProfile from_phases(double distance, double v0, double v1, double peak,
                                                 const std::array<double, 7>& durations, double max_jerk) noexcept;
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
  /// The first time [s] at which the profile has covered `s_mm` (s(t) does not decrease):
  /// bisection, for planning (where a piece of a chain starts in its profile).
  [[nodiscard]] double time_at(double s_mm) const noexcept;
  /// End time [s] of phase k (0..6), its jerk [mm/s^3] and the state at its end (as integrated).
  [[nodiscard]] double phase_end_time(int k) const noexcept { return start_time_[static_cast<std::size_t>(k) + 1]; }
  [[nodiscard]] double phase_jerk(int k) const noexcept { return jerk_[static_cast<std::size_t>(k)]; }
  [[nodiscard]] PathState sample_phase_end(int k) const noexcept { return start_[static_cast<std::size_t>(k) + 1]; }

 private:
  std::array<double, 8> start_time_{};  // start of phase k, [7] = end
  std::array<PathState, 8> start_{};    // state at the start of phase k, [7] = end
  std::array<double, 7> jerk_{};        // jerk during phase k
  double distance_ = 0.0;
  double peak_ = 0.0;
};

}  // namespace kontur::trajectory
