#pragma once
// Setpoints at the servo period from the trajectory's segments: setpoint k at time k T (computed, not summed),
// samples the current segment's profile for the distance along its piece and maps it to a point by
// the exact arc length (ArcLengthTable::u_after). The per-cycle path: noexcept, allocation-free,
// bounded, and it never frees (it only marks the segments it has passed; the planner frees them).
#include <cmath>
#include <cstddef>
#include <kontur/axes.hpp>
#include <kontur/program/move.hpp>
#include <kontur/trajectory/trajectory.hpp>

namespace kontur::trajectory {

/// The times of the servo cycles: cycle k at k T [s], computed, never summed. For a period that
/// is a whole number of nanoseconds (every real servo period) it is (k * T [ns]) / 1e9, the double
/// nearest to the exact decimal time (cycle 5270 at 1 ms is 5.27 s, not 5.2700000000000005);
/// otherwise k * T. The period's nanoseconds are found once, at construction.
class ServoClock {
 public:
  explicit ServoClock(double period_s) noexcept : period_(period_s) {
    const double ns = std::round(period_s * 1e9);
    if (ns >= 1.0 && std::abs(ns * 1e-9 - period_s) <= 1e-12 * period_s) ns_ = ns;
  }
  /// The period [s].
  [[nodiscard]] double period_s() const noexcept { return period_; }
  /// The time of cycle k [s].
  [[nodiscard]] double time_s(long k) const noexcept {
    const double kns = static_cast<double>(k) * ns_;
    return ns_ > 0.0 && kns < 9.0e15 ? kns / 1e9 : static_cast<double>(k) * period_;
  }

 private:
  double period_;     // [s]
  double ns_ = 0.0;   // the period in whole nanoseconds, 0 when it is not one
};

/// One setpoint of the servo loop.
struct Setpoint {
  double t_s = 0.0;                           ///< time since the start [s]
  AxisVector position = AxisVector::Zero(3);  ///< axis positions in the layout's order [mm] / [deg]
  double v_mm_s = 0.0;                        ///< planned path speed [mm/s]
  long source_line = 0;                       ///< line of the move it lies on (of the dwell, while dwelling)
  program::MoveId move = program::no_move;    ///< the move it lies on (no_move: unknown, e.g. read from a file)
  /// Only from a Sampler with derivatives on (else zero): the exact axis velocities [mm/s] or
  /// [deg/s] and accelerations [mm/s^2] or [deg/s^2] of the planned motion at this setpoint, and
  /// the path's acceleration [mm/s^2] and jerk [mm/s^3] (the derivatives of v_mm_s).
  AxisVector velocity = AxisVector::Zero(3);
  AxisVector acceleration = AxisVector::Zero(3);
  double a_mm_s2 = 0.0;
  double j_mm_s3 = 0.0;
};

class Sampler {
 public:
  /// Samples `trajectory` (kept by reference) every `period_s` [s]; positions in `layout`.
  /// With `derivatives`, each setpoint also gets its exact velocity and acceleration (the curve's
  /// first and second derivatives at its point: the segment stream fits them; segments/).
  Sampler(Trajectory& trajectory, double period_s, const AxisLayout& layout = AxisLayout::xyz(),
          bool derivatives = false) noexcept
      : trajectory_(&trajectory), clock_(period_s), layout_(layout), derivatives_(derivatives) {}
  /// The next setpoint: false when the trajectory has no segment for it yet (the planner must
  /// append more), or when done(). The first setpoint is the start point at t = 0.
  bool next(Setpoint& out) noexcept;
  /// True once the last setpoint (the end of the last segment, at rest) was given.
  [[nodiscard]] bool done() const noexcept { return end_given_; }
  /// Servo period [s].
  [[nodiscard]] double period_s() const noexcept { return clock_.period_s(); }
  /// The layout of the setpoints' positions.
  [[nodiscard]] const AxisLayout& layout() const noexcept { return layout_; }

 private:
  void emit(Setpoint& out, double t, const Vec3& p, const ExtraAxes& extra, double v, long line,
            program::MoveId move) const noexcept;
  // The velocity and acceleration of `out` on segment `m` at parameter u with path state `st`.
  void emit_derivatives(Setpoint& out, const Segment& m, double u, const PathState& st) const noexcept;
  /// The point at arc length s_ of `m`: C(u_) moved along the tangent by the arc-length error s_error_.
  [[nodiscard]] Vec3 point_at_s(const Segment& m) const noexcept;

  Trajectory* trajectory_;
  ServoClock clock_;  // the period and the times of the cycles
  AxisLayout layout_;
  bool derivatives_ = false;
  std::size_t current_ = 0;  // index of the current segment
  bool started_ = false;
  bool end_given_ = false;
  long cycle_ = 0;  // number of the last setpoint: its time is clock_.time_s(cycle_)
  double t_move_ = 0.0;       // time into the current segment [s]
  double s_error_ = 0.0;      // arc length at u_ minus s_ [mm] (ArcLengthTable::u_after)
  double u_ = 0.0, s_ = 0.0;  // parameter and distance on the curve of the last setpoint
};

}  // namespace kontur::trajectory
