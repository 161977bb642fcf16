#pragma once
// An independent check of setpoints against the machine and the programmed path, computed from
// the setpoints alone (finite differences) and the path's geometry: nothing of the planner is
// trusted. The core of `kontur verify` and of the tests that prove the planner.
#include <kontur/curve.hpp>
#include <kontur/machine.hpp>

#include <string>
#include <vector>

namespace kontur::verify {

/// One programmed move as the checker sees it.
struct PathMove {
  const Curve* curve = nullptr;  ///< the programmed path
  long source_line = 0;          ///< the line setpoints on it carry
};

/// A setpoint to check (as written by the planner: time, position, source line).
struct Sample {
  double t_s = 0.0;
  Vec3 position = Vec3::Zero();
  long source_line = 0;
};

/// Measured maxima and what they are measured against.
struct Report {
  long samples = 0;
  bool finite = true;                  ///< no NaN or infinity in any sample
  bool uniform_time = true;            ///< every step is one servo period (1e-9 relative)
  double max_velocity_ratio = 0.0;     ///< max over axes of |dx/dt| / limit (1 = at the limit)
  double max_acceleration_ratio = 0.0; ///< the same for the second difference
  double max_jerk_ratio = 0.0;         ///< the same for the third difference
  char worst_velocity_axis = ' ', worst_acceleration_axis = ' ', worst_jerk_axis = ' ';
  double max_path_error_mm = 0.0;      ///< largest distance of a setpoint from its move's path [mm]
  double max_chord_error_mm = 0.0;     ///< largest distance of the path from a cycle's chord [mm]
  double start_error_mm = 0.0;         ///< distance of the first setpoint from the path's start [mm]
  double end_error_mm = 0.0;           ///< distance of the last setpoint from the path's end [mm]
  /// True if every measure is within the machine's limits (1e-6 relative) and tolerances.
  [[nodiscard]] bool passed(const Machine& machine) const noexcept;
  /// What failed, one line each (empty if passed).
  [[nodiscard]] std::vector<std::string> failures(const Machine& machine) const;
};

/// Checks `samples` (in time order) against `machine` and the path `moves` (in order): each
/// sample is matched to the next move with its source line (samples never go back), and among
/// moves of one line (or where lines do not match) to the nearest of the next few.
[[nodiscard]] Report check(const std::vector<Sample>& samples, const std::vector<PathMove>& moves,
                           const Machine& machine);

}  // namespace kontur::verify
