#pragma once
// An independent check of setpoints against the machine and the programmed path, computed from
// the setpoints alone (finite differences) and the path's geometry: nothing of the planner is
// trusted. The core of `kontur verify` and of the tests that prove the planner.
#include <kontur/geometry/curve.hpp>
#include <kontur/machine.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace kontur::verify {

/// The programmed corner a blend replaces: the lines before -> corner -> after of the program.
struct ProgrammedCorner {
  Vec3 before = Vec3::Zero();  ///< start of the incoming line [mm]
  Vec3 corner = Vec3::Zero();  ///< the corner point [mm]
  Vec3 after = Vec3::Zero();   ///< end of the outgoing line [mm]
  double tolerance_mm = 0.0;   ///< the G64 tolerance the blend must keep [mm]
};

/// One move of the path as the checker sees it.
struct PathMove {
  const Curve* curve = nullptr;  ///< the path run (a programmed move, a trimmed line or a corner blend)
  long source_line = 0;          ///< the line setpoints on it carry
  /// A corner blend: the programmed corner it replaces (its largest distance from the two lines is
  /// checked against the tolerance); nullptr for any other move.
  const ProgrammedCorner* corner = nullptr;
};

/// A setpoint to check (as written by the planner: time, position, source line).
struct Sample {
  double t_s = 0.0;
  Vec3 position = Vec3::Zero();
  long source_line = 0;
};

/// The measures of one programmed move (block): over the setpoints the checker matched to it.
struct BlockStats {
  long source_line = 0;
  long samples = 0;                    ///< setpoints on this move (0: shorter than a period, skipped)
  long first_sample = -1;              ///< index of its first setpoint (-1 if none)
  long last_sample = -1;               ///< index of its last setpoint (-1 if none)
  double t_first_s = 0.0;              ///< time of its first setpoint [s] (0 if none)
  double t_last_s = 0.0;               ///< time of its last setpoint [s] (0 if none)
  double max_path_error_mm = 0.0;      ///< largest distance of its setpoints from its path [mm]
  double max_chord_error_mm = 0.0;     ///< largest bow of its chords (both ends on it) [mm]
  double max_velocity_ratio = 0.0;     ///< over its setpoints k: max over axes of the difference ending at k / limit
  double max_acceleration_ratio = 0.0; ///< the same for the second difference
  double max_jerk_ratio = 0.0;         ///< the same for the third difference
};

/// What the checker measured at one setpoint, handed to an Observer in time order.
struct SampleMeasure {
  std::size_t index = 0;     ///< index of the setpoint
  double t_s = 0.0;          ///< its time [s]
  Vec3 position = Vec3::Zero();  ///< [mm]
  /// Backward differences per axis, as the limits are checked: (p_k - p_{k-1}) / T [mm/s], then
  /// the second [mm/s^2] and third [mm/s^3] differences over T^2 and T^3; zero where there are
  /// not enough earlier setpoints (k < 1, 2, 3).
  Vec3 velocity = Vec3::Zero(), acceleration = Vec3::Zero(), jerk = Vec3::Zero();
  double velocity_ratio = 0.0, acceleration_ratio = 0.0, jerk_ratio = 0.0;  ///< max over axes / limit
  double path_error_mm = 0.0;   ///< distance from its move's path [mm]
  double chord_error_mm = 0.0;  ///< bow of the path from the chord ending here [mm] (0 at a move change)
  std::size_t move = 0;         ///< index into `moves` of the move it was matched to
};

/// Called once per setpoint, in order, by check() (only when every setpoint is finite).
using Observer = std::function<void(const SampleMeasure&)>;

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
  long blends = 0;                     ///< corner blends among the moves
  double max_blend_deviation_mm = 0.0; ///< largest distance of a blend from its programmed corner's lines [mm]
  double blend_tolerance_mm = 0.0;     ///< the tolerance of the blend with the largest deviation / tolerance [mm]
  double max_blend_deviation_ratio = 0.0;  ///< largest deviation / tolerance of a blend
  /// One per move, in the order of `moves` (empty when the check could not run: no setpoint,
  /// no move, or a setpoint not finite). Their maxima are the maxima above.
  std::vector<BlockStats> blocks;
  /// True if every measure is within the machine's limits (1e-6 relative) and tolerances (every
  /// blend within its corner's tolerance, tolerances::blend_deviation_relative).
  [[nodiscard]] bool passed(const Machine& machine) const noexcept;
  /// What failed, one line each (empty if passed).
  [[nodiscard]] std::vector<std::string> failures(const Machine& machine) const;
};

/// Largest distance [mm] of `curve` from the union of the segments [before, corner] and
/// [corner, after], sampled densely (tolerances::blend_deviation_samples per curve and a
/// golden-section search around the largest sample).
[[nodiscard]] double corner_deviation(const Curve& curve, const ProgrammedCorner& corner);

/// Checks `samples` (in time order) against `machine` and the path `moves` (in order): each
/// sample is matched to the next move with its source line (samples never go back), and among
/// moves of one line (or where lines do not match) to the nearest of the next few.
[[nodiscard]] Report check(const std::vector<Sample>& samples, const std::vector<PathMove>& moves,
                           const Machine& machine);
/// The same, and `observer` (if set) receives every setpoint's measures, in order (for plots).
[[nodiscard]] Report check(const std::vector<Sample>& samples, const std::vector<PathMove>& moves,
                           const Machine& machine, const Observer& observer);

}  // namespace kontur::verify
