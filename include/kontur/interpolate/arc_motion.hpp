#pragma once
// Motion along an arc (circle or conic), methods.md sections 4.5 and 5.8: the seed programs'
// modes, N equal steps of the angle (central angle of a circle, focal angle of a conic) at a
// constant angular speed, and Kontur's constant-feed mode, setpoints at a servo period with the
// arc length exact (ArcLengthTable::u_of_s). Planning (the constructors) may allocate and throw;
// sampling (sample) is noexcept and allocation-free.
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/length.hpp>

#include <vector>

namespace kontur {

/// The seed's problem types.
enum class AngularProblem {
  omega_given = 1,  ///< angular speed omega given: t = theta / omega
  time_given = 2,   ///< time t given: omega = theta / t
};

/// Timing of the seed programs' mode.
struct AngularTiming {
  double sweep_rad = 0.0;        ///< angle of the arc (theta13 or theta15) [rad]
  double length_mm = 0.0;        ///< length of the arc [mm]
  double omega_rad_s = 0.0;      ///< angular speed [rad/s]
  double time_s = 0.0;           ///< duration t [s]
  int steps = 0;                 ///< N
  double dt_s = 0.0;             ///< t / N [s]
  double dphi_rad = 0.0;         ///< sweep / N [rad]
  double mean_speed_mm_s = 0.0;  ///< V = length / t [mm/s] (the seed's (2.61), corrected)
};

/// Computes t or omega, dt and dphi. Throws InputError: "omega-positive" or "time-positive"
/// (value not finite and > 0), "steps-positive" (N < 1), "sweep-positive", "length-positive".
[[nodiscard]] AngularTiming angular_timing(double sweep_rad, double length_mm, AngularProblem problem, double value,
                                           int steps);

/// One setpoint.
struct MotionSample {
  double time_s = 0.0;     ///< time from the start [s]
  double u = 0.0;          ///< curve parameter
  double arc_mm = 0.0;     ///< arc length from the start [mm] (constant-feed mode; 0 in the angular mode)
  Vec3 point = Vec3::Zero();  ///< position in the machine frame [mm]
};

/// The seed's mode: N equal steps of the curve parameter (the angle for a HelixArc, u in [0, 1],
/// and for a ConicArc, u = swept focal angle) at uniform time steps. The last sample is the end
/// point given by the user (the formula reaches it to rounding; the tests check 1e-12).
class AngularStepper {
public:
  /// Keeps a reference to the curve, which must outlive the stepper.
  AngularStepper(const Curve& curve, const AngularTiming& timing, const Vec3& end_point);
  /// Number of samples, N + 1.
  [[nodiscard]] int samples() const noexcept { return steps_ + 1; }
  /// Sample i in [0, N] (clamped). noexcept, no allocation.
  [[nodiscard]] MotionSample sample(int i) const noexcept;

private:
  const Curve* curve_;
  int steps_;
  double dt_, du_;
  Vec3 end_;
};

/// Speed along the path of the angular mode [mm/s]: |C'(u)| du/dt, sampled.
struct SpeedVariation {
  double min_mm_s = 0.0;   ///< smallest speed [mm/s]
  double max_mm_s = 0.0;   ///< largest speed [mm/s]
  double mean_mm_s = 0.0;  ///< length / time [mm/s]
  /// (max - min) / mean: 0 for a circle, the variation of the focal-angle steps of a conic.
  [[nodiscard]] double relative_variation() const noexcept {
    return mean_mm_s > 0.0 ? (max_mm_s - min_mm_s) / mean_mm_s : 0.0;
  }
};

/// Speed of the angular mode over the arc, from `samples` evenly spaced parameters (and the ends).
[[nodiscard]] SpeedVariation angular_speed_variation(const Curve& curve, const AngularTiming& timing,
                                                     int samples = 4096);

/// Kontur's mode: constant feed F [mm/min] along the arc, one setpoint per servo period T [s],
/// s_k = min(k F T / 60, L), u_k = u(s_k) from the arc-length table; the last sample is the end
/// point given by the user, reached after ceil(L / (F T / 60)) periods. Up to `precompute_limit`
/// periods the parameters u_k are computed at construction (planning: one u_of_s each, a few
/// microseconds), so that a sample is one curve evaluation; beyond it each sample calls u_of_s.
class ConstantFeedStepper {
public:
  /// Keeps references to the curve and the table, which must outlive the stepper. Throws
  /// InputError "feed-positive" or "period-positive" (not finite and > 0) and "too-many-periods"
  /// (more than max_periods setpoints).
  ConstantFeedStepper(const Curve& curve, const ArcLengthTable& table, const Vec3& end_point, double feed_mm_min,
                      double period_s, long max_periods = 100'000'000, long precompute_limit = 1'000'000);
  /// Number of samples (periods + 1).
  [[nodiscard]] long samples() const noexcept { return periods_ + 1; }
  /// Path advance per period, F T / 60 [mm].
  [[nodiscard]] double step_mm() const noexcept { return step_; }
  /// Time to run the arc, L / (F / 60) [s].
  [[nodiscard]] double time_s() const noexcept { return length_ / step_ * period_; }
  [[nodiscard]] double length_mm() const noexcept { return length_; }
  [[nodiscard]] double feed_mm_min() const noexcept { return feed_; }
  [[nodiscard]] double period_s() const noexcept { return period_; }
  /// Sample k in [0, periods] (clamped). noexcept, no allocation.
  [[nodiscard]] MotionSample sample(long k) const noexcept;

private:
  const Curve* curve_;
  const ArcLengthTable* table_;
  Vec3 end_;
  double feed_, period_, step_, length_;
  long periods_;
  std::vector<double> u_;  // u_k for k < periods_, when precomputed
};

}  // namespace kontur
