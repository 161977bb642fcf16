#include <algorithm>
#include <cmath>
#include <kontur/plan/chain_profile.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <vector>

namespace kontur::plan {

namespace {

using trajectory::PathState;
using trajectory::ProfilePhase;

struct Kin {
  double s = 0.0, v = 0.0, a = 0.0;  // [mm], [mm/s], [mm/s^2]
};

Kin advance(const Kin& x, double j, double dt) {
  return {x.s + x.v * dt + 0.5 * x.a * dt * dt + j * dt * dt * dt / 6.0, x.v + x.a * dt + 0.5 * j * dt * dt,
          x.a + j * dt};
}

// The lowest and the highest speed [mm/s] over a step of jerk j and duration dt from x: at its
// ends, or where the acceleration passes zero inside it.
struct SpeedRange {
  double lo = 0.0, hi = 0.0;
};

SpeedRange speed_range(const Kin& x, double j, double dt, const Kin& end) {
  SpeedRange r{std::min(x.v, end.v), std::max(x.v, end.v)};
  if (j != 0.0) {
    const double tau = -x.a / j;
    if (tau > 0.0 && tau < dt) {
      const double v = x.v + x.a * tau + 0.5 * j * tau * tau;
      r.lo = std::min(r.lo, v);
      r.hi = std::max(r.hi, v);
    }
  }
  return r;
}

// Bringing the acceleration to zero at full jerk: its duration [s], jerk, distance [mm] and the
// speed it ends at [mm/s].
struct Ease {
  double duration_s = 0.0, jerk = 0.0, distance_mm = 0.0, v_end = 0.0;
};

Ease ease(const Kin& x, double max_jerk) {
  Ease e;
  e.v_end = x.v;
  if (x.a == 0.0) return e;
  e.jerk = x.a > 0.0 ? -max_jerk : max_jerk;
  e.duration_s = std::abs(x.a) / max_jerk;
  const Kin y = advance(x, e.jerk, e.duration_s);
  e.distance_mm = y.s - x.s;
  e.v_end = y.v;
  return e;
}

class ChainPlanner {
 public:
  // cautious: aim each junction's speed so low that, landing there at zero acceleration, every
  // later junction and the end stay in reach (slower, but it plans chains the other cannot).
  ChainPlanner(std::span<const CapStretch> stretches, double v0, double v1, const PathLimits& limits, bool cautious)
      : v0_(v0), v1_(v1), a_(limits.max_acceleration), j_(limits.max_jerk) {
    bounds_.push_back(0.0);
    for (const CapStretch& c : stretches) {
      bounds_.push_back(bounds_.back() + c.length_mm);
      caps_.push_back(c.cap_mm_s);
    }
    length_ = bounds_.back();
    double top = 0.0;
    for (double c : caps_) top = std::max(top, c);
    slack_v_ = tolerances::chain_profile_speed_slack * top;
    junction_speed_.assign(caps_.size() + 1, 0.0);
    junction_speed_[caps_.size()] = v1_;
    const PathLimits reach{top, a_, j_};
    for (std::size_t m = caps_.size() - 1; m >= 1; --m)
      junction_speed_[m] = std::min(caps_[m - 1], caps_[m]);
    if (cautious)  // backwards: slow enough to brake to the next junction's speed within the stretch
      for (std::size_t m = caps_.size() - 1; m >= 1; --m)
        junction_speed_[m] = std::min(junction_speed_[m], reachable_velocity(junction_speed_[m + 1],
                                                                             bounds_[m + 1] - bounds_[m], reach));
  }

  // Smallest cap over the open interval (a, b) of distance [mm].
  [[nodiscard]] double min_cap(double a, double b) const {
    std::size_t k = stretch_at(a);
    double c = caps_[k];
    while (k + 1 < caps_.size() && bounds_[k + 1] < b) c = std::min(c, caps_[++k]);
    return c;
  }

  // The stretch containing distance s (the later one at a boundary).
  [[nodiscard]] std::size_t stretch_at(double s) const {
    const auto it = std::upper_bound(bounds_.begin() + 1, bounds_.end() - 1, s);
    return static_cast<std::size_t>(it - (bounds_.begin() + 1));
  }

  // The speed [mm/s] at junction m (1 <= m < caps_.size()): at most both caps; at the end
  // (m = caps_.size()), exactly v1.
  [[nodiscard]] double junction_speed(std::size_t m) const { return junction_speed_[m]; }

  // The junction after `from` (or the end) with the least room from x, and that room [mm].
  [[nodiscard]] std::pair<std::size_t, double> tightest_after(const Kin& x, const Ease& e, std::size_t from) const {
    std::size_t bind = caps_.size();
    double least = room(x, e, bind);
    for (std::size_t m = from + 1; m < caps_.size(); ++m) {
      const double r = room(x, e, m);
      if (r < least) {
        least = r;
        bind = m;
      }
    }
    return {bind, least};
  }

  // Room left [mm] for the manoeuvre from x towards junction m (speed at most junction_speed(m)
  // there) or the end (speed exactly v1); negative if it no longer fits; +infinity if that
  // junction does not ask for braking.
  [[nodiscard]] double room(const Kin& x, const Ease& e, std::size_t m) const {
    const bool end = m == caps_.size();
    const double w = junction_speed(m);
    if (!end && e.v_end <= w) return std::numeric_limits<double>::infinity();
    return bounds_[m] - x.s - e.distance_mm - velocity_change_distance(e.v_end, w, a_, j_);
  }

  // True if from x every junction ahead and the end can still be met.
  [[nodiscard]] bool safe(const Kin& x) const {
    const Ease e = ease(x, j_);
    if (e.v_end < 0.0) return false;
    if (std::max(x.v, e.v_end) > min_cap(x.s, x.s + e.distance_mm) + slack_v_) return false;
    const double reach = e.distance_mm + 2.0 * velocity_change_distance(e.v_end, 0.0, a_, j_);
    for (std::size_t m = stretch_at(x.s) + 1; m < caps_.size() && bounds_[m] - x.s <= reach; ++m)
      if (room(x, e, m) < 0.0) return false;
    return room(x, e, caps_.size()) >= 0.0;
  }

  // The profile, or none if the steps ran out or the check failed.
  [[nodiscard]] std::optional<trajectory::PathProfile> plan(double dt, double time_bound_s) {
    const double cap_all = *std::min_element(caps_.begin(), caps_.end());
    std::vector<ProfilePhase> phases;
    Kin x{0.0, v0_, 0.0};
    double t = 0.0;
    const auto max_steps =
        static_cast<std::size_t>(tolerances::chain_profile_max_steps_per_flat * time_bound_s / dt) + 64;
    std::size_t steps = 0;
    for (;;) {
      if (++steps > max_steps) return std::nullopt;
      bool moved = false;
      for (const double want : {j_, 0.0, -j_}) {
        const double j = std::clamp(want, (-a_ - x.a) / dt, (a_ - x.a) / dt);
        const Kin y = advance(x, j, dt);
        if (!(y.s < length_) || !(y.s > x.s)) continue;
        const SpeedRange r = speed_range(x, j, dt, y);
        if (r.lo < 0.0 || r.hi > min_cap(x.s, y.s) + slack_v_ || !safe(y)) continue;
        phases.push_back({t, {x.s, x.v, x.a, j}, j});
        t += dt;
        x = y;
        moved = true;
        break;
      }
      if (moved) continue;
      // No step is safe: carry out the manoeuvre towards the junction that binds. It lands there
      // at zero acceleration; where a later junction could no longer be met from that landing,
      // it aims at that one instead (passing the first below its cap, as fits() checks).
      const Ease e = ease(x, j_);
      std::size_t bind = tightest_after(x, e, stretch_at(x.s)).first;
      while (bind < caps_.size()) {
        const Kin land{bounds_[bind], junction_speed(bind), 0.0};
        const auto [next, r] = tightest_after(land, ease(land, j_), bind);
        if (!(r < 0.0)) break;
        bind = next;
      }
      if (e.duration_s > 0.0) {
        phases.push_back({t, {x.s, x.v, x.a, e.jerk}, e.jerk});
        t += e.duration_s;
        x = advance(x, e.jerk, e.duration_s);
        x.a = 0.0;
      }
      const bool end = bind == caps_.size();
      const double w = junction_speed(bind);
      const double target = bounds_[bind], dist = target - x.s;
      if (!(dist >= 0.0) || x.v < 0.0) return std::nullopt;
      PathLimits l{std::max({x.v, w, x.v > slack_v_ ? 0.0 : cap_all}), a_, j_};
      const ScurveProfile c = plan_scurve(dist, x.v, w, l);
      if (!(std::abs(c.end_velocity() - w) <= slack_v_)) return std::nullopt;
      trajectory::append_phases(c, t, x.s, phases);
      t += c.duration();
      x = {target, w, 0.0};
      if (end) break;
    }
    if (!fits(phases, t)) return std::nullopt;
    return trajectory::PathProfile(std::move(phases), t, {length_, v1_, 0.0, 0.0});
  }

  // Every phase below the cap of each stretch it runs through, over the part of it inside that
  // stretch (a phase that ends or starts on a junction counts only to the stretches it runs
  // inside; a braking phase may cross into a lower cap once its speed is below it), the speed
  // never negative.
  [[nodiscard]] bool fits(const std::vector<ProfilePhase>& phases, double duration_s) const {
    const double ds = tolerances::chain_profile_boundary_mm;
    for (std::size_t k = 0; k < phases.size(); ++k) {
      const ProfilePhase& p = phases[k];
      const double dt = (k + 1 < phases.size() ? phases[k + 1].t0_s : duration_s) - p.t0_s;
      const Kin x{p.start.s, p.start.v, p.start.a};
      const Kin y = advance(x, p.jerk, dt);
      const SpeedRange r = speed_range(x, p.jerk, dt, y);
      if (r.lo < -slack_v_ || std::abs(x.a) > a_ * (1.0 + 1e-9) || std::abs(p.jerk) > j_ * (1.0 + 1e-9)) return false;
      const double lo = std::min(x.s + ds, 0.5 * (x.s + y.s)), hi = std::max(y.s - ds, 0.5 * (x.s + y.s));
      const std::size_t first = stretch_at(lo), last = stretch_at(hi);
      if (first == last) {
        if (r.hi > caps_[first] + slack_v_) return false;
        continue;
      }
      // Crossing junctions: each part against its own stretch's cap.
      double t_a = 0.0;
      for (std::size_t m = first; m <= last; ++m) {
        const double t_b = m == last ? dt : crossing_time(x, p.jerk, dt, bounds_[m + 1]);
        const Kin a = advance(x, p.jerk, t_a), b = advance(x, p.jerk, t_b);
        if (speed_range(a, p.jerk, t_b - t_a, b).hi > caps_[m] + slack_v_) return false;
        t_a = t_b;
      }
    }
    return true;
  }

  // The time [s] within [0, dt] at which a phase of jerk j from x reaches distance s_mm (its
  // distance does not fall: the speed is not negative), by bisection to the last bit.
  [[nodiscard]] static double crossing_time(const Kin& x, double j, double dt, double s_mm) {
    double lo = 0.0, hi = dt;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (advance(x, j, mid).s < s_mm ? lo : hi) = mid;
    }
    return hi;
  }

 private:
  double v0_, v1_, a_, j_;
  std::vector<double> bounds_, caps_, junction_speed_;  // junction_speed_[m]: at bounds_[m], m >= 1
  double length_ = 0.0, slack_v_ = 0.0;
};

}  // namespace

std::optional<trajectory::PathProfile> plan_chain_profile(std::span<const CapStretch> stretches, double v0,
                                                          double v1, const PathLimits& limits, double step_s,
                                                          double time_bound_s) {
  if (stretches.empty() || !(step_s > 0.0) || !(limits.max_acceleration > 0.0) || !(limits.max_jerk > 0.0))
    return std::nullopt;
  if (auto p = ChainPlanner(stretches, v0, v1, limits, false).plan(step_s, time_bound_s)) return p;
  return ChainPlanner(stretches, v0, v1, limits, true).plan(step_s, time_bound_s);
}

}  // namespace kontur::plan
