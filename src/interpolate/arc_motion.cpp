// Motion along an arc: the seed programs' angular modes and Kontur's constant feed.
#include <kontur/interpolate/arc_motion.hpp>
#include <kontur/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace kontur {

AngularTiming angular_timing(double sweep_rad, double length_mm, AngularProblem problem, double value, int steps) {
  if (!(std::isfinite(sweep_rad) && sweep_rad > 0.0))
    throw InputError("sweep-positive", fmt::format("arc angle {} rad: must be finite and > 0", sweep_rad));
  if (!(std::isfinite(length_mm) && length_mm > 0.0))
    throw InputError("length-positive", fmt::format("arc length {} mm: must be finite and > 0", length_mm));
  if (problem == AngularProblem::omega_given && !(std::isfinite(value) && value > 0.0))
    throw InputError("omega-positive", fmt::format("omega = {} rad/s: the angular speed must be finite and > 0", value));
  if (problem == AngularProblem::time_given && !(std::isfinite(value) && value > 0.0))
    throw InputError("time-positive", fmt::format("t = {} s: the time must be finite and > 0", value));
  if (steps < 1) throw InputError("steps-positive", fmt::format("N = {}: the number of steps must be >= 1", steps));
  AngularTiming t;
  t.sweep_rad = sweep_rad;
  t.length_mm = length_mm;
  t.steps = steps;
  if (problem == AngularProblem::omega_given) {
    t.omega_rad_s = value;
    t.time_s = sweep_rad / value;  // seed (2.58) / (3.182)
  } else {
    t.time_s = value;
    t.omega_rad_s = sweep_rad / value;  // seed (2.59) / (3.183)
  }
  if (!(std::isfinite(t.time_s) && t.time_s > 0.0 && std::isfinite(t.omega_rad_s) && t.omega_rad_s > 0.0))
    throw InputError(problem == AngularProblem::omega_given ? "omega-positive" : "time-positive",
                     fmt::format("omega = {} rad/s and t = {} s: out of the range of double precision", t.omega_rad_s,
                                 t.time_s));
  t.dt_s = t.time_s / steps;
  t.dphi_rad = sweep_rad / steps;
  t.mean_speed_mm_s = length_mm / t.time_s;  // seed (2.61), corrected: V = R theta13 / t
  return t;
}

AngularStepper::AngularStepper(const Curve& curve, const AngularTiming& timing, const Vec3& end_point)
    : curve_(&curve), steps_(timing.steps), dt_(timing.dt_s), du_((curve.u_max() - curve.u_min()) / timing.steps),
      end_(end_point) {
  if (steps_ < 1) throw InputError("steps-positive", fmt::format("N = {}: the number of steps must be >= 1", steps_));
}

MotionSample AngularStepper::sample(int i) const noexcept {
  i = std::clamp(i, 0, steps_);
  MotionSample m;
  if (i == steps_) {
    m.time_s = dt_ * steps_;
    m.u = curve_->u_max();
    m.point = end_;
  } else {
    m.time_s = dt_ * i;
    m.u = curve_->u_min() + du_ * i;
    m.point = curve_->point(m.u);
  }
  return m;
}

SpeedVariation angular_speed_variation(const Curve& curve, const AngularTiming& timing, int samples) {
  SpeedVariation v;
  const double u0 = curve.u_min(), u1 = curve.u_max();
  const double du_dt = (u1 - u0) / timing.time_s;
  samples = std::max(samples, 2);
  v.min_mm_s = v.max_mm_s = curve.speed(u0) * du_dt;
  for (int i = 1; i <= samples; ++i) {
    const double sp = curve.speed(u0 + (u1 - u0) * i / samples) * du_dt;
    v.min_mm_s = std::min(v.min_mm_s, sp);
    v.max_mm_s = std::max(v.max_mm_s, sp);
  }
  v.mean_mm_s = timing.mean_speed_mm_s;
  return v;
}

ConstantFeedStepper::ConstantFeedStepper(const Curve& curve, const ArcLengthTable& table, const Vec3& end_point,
                                         double feed_mm_min, double period_s, long max_periods, long precompute_limit)
    : curve_(&curve), table_(&table), end_(end_point), feed_(feed_mm_min), period_(period_s), step_(0.0),
      length_(table.length_mm()), periods_(0) {
  if (!(std::isfinite(feed_mm_min) && feed_mm_min > 0.0))
    throw InputError("feed-positive", fmt::format("F = {} mm/min: the feed must be finite and > 0", feed_mm_min));
  if (!(std::isfinite(period_s) && period_s > 0.0))
    throw InputError("period-positive", fmt::format("T = {} s: the servo period must be finite and > 0", period_s));
  step_ = feed_mm_min / 60.0 * period_s;
  // A whole number of periods up to rounding does not add a final period of 1e-16 mm.
  const double n = std::ceil(length_ / step_ * (1.0 - 1e-12));
  if (!(n <= static_cast<double>(max_periods)))
    throw InputError("too-many-periods",
                     fmt::format("F = {} mm/min and T = {} s give {:.3g} setpoints for {:.6g} mm; at most {} are allowed",
                                 feed_mm_min, period_s, n, length_, max_periods));
  periods_ = std::max(1L, static_cast<long>(n));
  if (periods_ <= precompute_limit) {
    u_.resize(static_cast<std::size_t>(periods_));
    // Each period from the one before: only the step is integrated (ArcLengthTable::u_after).
    u_[0] = curve.u_min();
    for (long k = 1; k < periods_; ++k) {
      const double s0 = step_ * static_cast<double>(k - 1), s1 = step_ * static_cast<double>(k);
      const double previous = u_[static_cast<std::size_t>(k - 1)];
      const double speed = curve.speed(previous);
      const double hint = speed > 0.0 ? previous + (s1 - s0) / speed : previous;
      u_[static_cast<std::size_t>(k)] = table.u_after(previous, s0, s1, hint);
    }
  }
}

MotionSample ConstantFeedStepper::sample(long k) const noexcept {
  k = std::clamp(k, 0L, periods_);
  MotionSample m;
  m.time_s = period_ * static_cast<double>(k);
  if (k == periods_) {
    m.arc_mm = length_;
    m.u = curve_->u_max();
    m.point = end_;
  } else {
    m.arc_mm = step_ * static_cast<double>(k);
    m.u = u_.empty() ? table_->u_of_s(m.arc_mm) : u_[static_cast<std::size_t>(k)];
    m.point = curve_->point(m.u);
  }
  return m;
}

}  // namespace kontur
