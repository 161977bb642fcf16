#include <algorithm>
#include <cmath>
#include <kontur/plan/scurve.hpp>

#include "bisection.hpp"

namespace kontur::plan {
namespace {

using detail::fits;

// Phases of one speed change from va to vb (vb >= va): jerk time and constant-acceleration time.
struct Change {
  double tj = 0.0;  // duration of each jerk phase [s]
  double ta = 0.0;  // duration of the constant-acceleration phase [s]
  double a = 0.0;   // peak acceleration reached [mm/s^2]
};

Change change_phases(double va, double vb, double amax, double jmax) noexcept {
  const double dv = std::abs(vb - va);
  Change c;
  if (dv * jmax <= amax * amax) {  // the acceleration limit is not reached: a triangle
    c.tj = std::sqrt(dv / jmax);
    c.ta = 0.0;
    c.a = jmax * c.tj;
  } else {
    c.tj = amax / jmax;
    c.ta = dv / amax - c.tj;
    c.a = amax;
  }
  return c;
}

}  // namespace

double velocity_change_time(double va, double vb, double amax, double jmax) noexcept {
  const Change c = change_phases(va, vb, amax, jmax);
  return 2.0 * c.tj + c.ta;
}

double velocity_change_distance(double va, double vb, double amax, double jmax) noexcept {
  return 0.5 * (va + vb) * velocity_change_time(va, vb, amax, jmax);
}

double reachable_velocity(double v_from, double distance, const PathLimits& l) noexcept {
  if (!(distance > 0.0)) return v_from;
  const auto excess = [&](double v) {
    return detail::fit_excess(velocity_change_distance(v_from, v, l.max_acceleration, l.max_jerk), distance);
  };
  const double e_max = excess(l.max_velocity);
  if (e_max <= 0.0) return l.max_velocity;
  return narrow_and_bisect(v_from, l.max_velocity, excess(v_from), e_max, excess).lo;
}

double braking_velocity(double v_after, double distance, const PathLimits& l) noexcept {
  const double a = l.max_acceleration, j = l.max_jerk;
  // The longest braking from v to any end speed in [v_after, v].
  auto worst = [&](double v) {
    double d = velocity_change_distance(v_after, v, a, j);
    for (const double w : {v / 3.0, a * a / (2.0 * j)})
      if (w > v_after && w < v) d = std::max(d, velocity_change_distance(w, v, a, j));
    return d;
  };
  if (!(distance > 0.0)) return v_after;
  const double e_max = detail::fit_excess(worst(l.max_velocity), distance);
  if (e_max <= 0.0) return l.max_velocity;
  const auto excess = [&](double v) { return detail::fit_excess(worst(v), distance); };
  return narrow_and_bisect(v_after, l.max_velocity, excess(v_after), e_max, excess).lo;
}

ScurveProfile plan_scurve(double distance, double v0, double v1, const PathLimits& l) {
  const double amax = l.max_acceleration, jmax = l.max_jerk, vmax = l.max_velocity;
  distance = std::max(distance, 0.0);
  v0 = std::clamp(v0, 0.0, vmax);
  v1 = std::clamp(v1, 0.0, vmax);
  // An end speed that cannot be reached (speeding up) within the distance is lowered; a start
  // speed too high to brake to v1 keeps v1 at the lowest speed reachable by braking.
  if (v1 > v0) v1 = std::min(v1, reachable_velocity(v0, distance, l));
  if (v0 > v1 && !fits(velocity_change_distance(v1, v0, amax, jmax), distance)) {
    // Braking to v1 does not fit. The braking distance is not monotone in the end speed (ending
    // at rest needs the last jerk phase): it rises from v = 0 to a peak and falls to 0 at v0.
    if (fits(velocity_change_distance(0.0, v0, amax, jmax), distance)) {
      // A full stop fits (v1 is on the rising part, or beyond the peak): end at the largest speed
      // below v1 that fits, slower than asked and never faster (the predicate "fits" is monotone
      // on [0, v1]: true up to a point on the rising part, false after it).
      const Bracket b =
          bisect(0.0, v1, [&](double v) { return fits(velocity_change_distance(v, v0, amax, jmax), distance); });
      v1 = b.lo;
    } else {
      // Not even a stop fits: the lowest speed reachable by braking within the distance (on the
      // falling part).
      const Bracket b =
          bisect(0.0, v0, [&](double v) { return !fits(velocity_change_distance(v, v0, amax, jmax), distance); });
      v1 = b.hi;
    }
  }
  // Peak speed: the largest vp in [max(v0, v1), vmax] whose two changes fit in the distance.
  auto needed = [&](double vp) {
    return velocity_change_distance(v0, vp, amax, jmax) + velocity_change_distance(v1, vp, amax, jmax);
  };
  const double floor_v = std::max(v0, v1);
  double vp = vmax;
  double cruise = 0.0;
  if (fits(needed(vmax), distance)) {
    cruise = vmax > 0.0 ? std::max(0.0, distance - needed(vmax)) / vmax : 0.0;
  } else {
    const Bracket b = bisect(floor_v, vmax, [&](double v) { return fits(needed(v), distance); });
    vp = b.lo;
    // What the changes leave of the distance (rounding, or the floor when v0 -> v1 alone is
    // longer) is cruised at the peak speed.
    cruise = vp > 0.0 ? std::max(0.0, distance - needed(vp)) / vp : 0.0;
  }
  const Change up = change_phases(v0, vp, amax, jmax);
  const Change down = change_phases(v1, vp, amax, jmax);
  const std::array<double, 7> durations = {up.tj, up.ta, up.tj, cruise, down.tj, down.ta, down.tj};
  return ScurveProfile::from_phases(distance, v0, v1, vp, durations, jmax);
}

}  // namespace kontur::plan
