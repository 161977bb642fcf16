#include <kontur/plan/scurve.hpp>

#include <algorithm>
#include <cmath>

namespace kontur::plan {
namespace {

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

constexpr int kBisections = 200;  // bounded; stops earlier when the interval cannot shrink

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
  if (velocity_change_distance(v_from, l.max_velocity, l.max_acceleration, l.max_jerk) <= distance) return l.max_velocity;
  double lo = v_from, hi = l.max_velocity;
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (velocity_change_distance(v_from, mid, l.max_acceleration, l.max_jerk) <= distance) lo = mid; else hi = mid;
  }
  return lo;
}

PathState ScurveProfile::sample(double t) const noexcept {
  if (!(t > 0.0)) return start_[0];
  if (t >= start_time_[7]) return start_[7];
  int k = 0;
  while (k < 6 && t >= start_time_[static_cast<std::size_t>(k + 1)]) ++k;
  const auto kk = static_cast<std::size_t>(k);
  const double tau = t - start_time_[kk];
  const PathState& p = start_[kk];
  const double j = jerk_[kk];
  PathState out;
  out.j = j;
  out.a = p.a + j * tau;
  out.v = p.v + p.a * tau + 0.5 * j * tau * tau;
  out.s = p.s + p.v * tau + 0.5 * p.a * tau * tau + j * tau * tau * tau / 6.0;
  // Rounding must not move past the end.
  out.s = std::min(out.s, distance_);
  out.v = std::max(out.v, 0.0);
  return out;
}

ScurveProfile plan_scurve(double distance, double v0, double v1, const PathLimits& l) {
  const double amax = l.max_acceleration, jmax = l.max_jerk, vmax = l.max_velocity;
  distance = std::max(distance, 0.0);
  v0 = std::clamp(v0, 0.0, vmax);
  v1 = std::clamp(v1, 0.0, vmax);
  // An end speed that cannot be reached (speeding up) within the distance is lowered; a start
  // speed too high to brake to v1 keeps v1 at the lowest speed reachable by braking.
  if (v1 > v0) v1 = std::min(v1, reachable_velocity(v0, distance, l));
  if (v0 > v1) v1 = std::max(v1, [&] {
    // lowest speed reachable from v0 by braking within the distance
    if (velocity_change_distance(0.0, v0, amax, jmax) <= distance) return 0.0;
    double lo = 0.0, hi = v0;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      if (velocity_change_distance(mid, v0, amax, jmax) <= distance) hi = mid; else lo = mid;
    }
    return hi;
  }());
  // Peak speed: the largest vp in [max(v0, v1), vmax] whose two changes fit in the distance.
  auto needed = [&](double vp) {
    return velocity_change_distance(v0, vp, amax, jmax) + velocity_change_distance(v1, vp, amax, jmax);
  };
  const double floor_v = std::max(v0, v1);
  double vp = vmax;
  double cruise = 0.0;
  if (needed(vmax) <= distance) {
    cruise = vmax > 0.0 ? (distance - needed(vmax)) / vmax : 0.0;
  } else {
    double lo = floor_v, hi = vmax;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      if (needed(mid) <= distance) lo = mid; else hi = mid;
    }
    vp = lo;
    // What the changes leave of the distance (rounding, or the floor when v0 -> v1 alone is
    // longer) is cruised at the peak speed.
    cruise = vp > 0.0 ? std::max(0.0, distance - needed(vp)) / vp : 0.0;
  }
  const Change up = change_phases(v0, vp, amax, jmax);
  const Change down = change_phases(v1, vp, amax, jmax);
  ScurveProfile p;
  p.distance_ = distance;
  p.peak_ = vp;
  const std::array<double, 7> durations = {up.tj, up.ta, up.tj, cruise, down.tj, down.ta, down.tj};
  p.jerk_ = {jmax, 0.0, -jmax, 0.0, -jmax, 0.0, jmax};
  p.start_[0] = {0.0, v0, 0.0, 0.0};
  p.start_time_[0] = 0.0;
  for (std::size_t k = 0; k < 7; ++k) {
    const PathState& s = p.start_[k];
    const double d = durations[k], j = p.jerk_[k];
    PathState e;
    e.a = s.a + j * d;
    e.v = s.v + s.a * d + 0.5 * j * d * d;
    e.s = s.s + s.v * d + 0.5 * s.a * d * d + j * d * d * d / 6.0;
    p.start_[k + 1] = e;
    p.start_time_[k + 1] = p.start_time_[k] + d;
  }
  // The end is exact by definition: the phases cover the distance up to rounding.
  p.start_[7] = {distance, v1, 0.0, 0.0};
  return p;
}

}  // namespace kontur::plan
