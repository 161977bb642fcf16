#include <algorithm>
#include <array>
#include <bit>
#include <iterator>
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

// The smallest of a list's values over a range of its indices, in constant time (a sparse table
// of the minima over ranges of 1, 2, 4, ... values).
class RangeMin {
 public:
  RangeMin() = default;
  explicit RangeMin(const std::vector<double>& v) {
    levels_.push_back(v);
    for (std::size_t w = 1; 2 * w <= v.size(); w *= 2) {
      const std::vector<double>& prev = levels_.back();
      std::vector<double> next(prev.size() - w);
      for (std::size_t i = 0; i < next.size(); ++i) next[i] = std::min(prev[i], prev[i + w]);
      levels_.push_back(std::move(next));
    }
  }
  // The value at index i.
  [[nodiscard]] double operator[](std::size_t i) const { return levels_[0][i]; }
  // The smallest over indices first .. last (first <= last).
  [[nodiscard]] double operator()(std::size_t first, std::size_t last) const {
    const auto k = static_cast<std::size_t>(std::bit_width(last - first + 1) - 1);
    return std::min(levels_[k][first], levels_[k][last + 1 - (std::size_t{1} << k)]);
  }

 private:
  std::vector<std::vector<double>> levels_;
};

// The smallest acceleration [mm/s^2] and jerk [mm/s^3] over a run of stretches.
struct Lim {
  double a = std::numeric_limits<double>::infinity(), j = std::numeric_limits<double>::infinity();
  void take(double a_k, double j_k) noexcept {
    a = std::min(a, a_k);
    j = std::min(j, j_k);
  }
};

class ChainPlanner {
 public:
  // cautious: aim each junction's speed so low that, landing there at zero acceleration, every
  // later junction and the end stay in reach (slower, but it plans chains the other cannot).
  ChainPlanner(std::span<const CapStretch> stretches, double v0, double v1, const PathLimits& limits, bool cautious)
      : v0_(v0), v1_(v1), stretches_(stretches), limits_(limits) {
    bounds_.push_back(0.0);
    for (const CapStretch& c : stretches) {
      bounds_.push_back(bounds_.back() + c.length_mm);
      caps_.push_back(c.cap_mm_s);
      banded_ = banded_ || c.bands.n > 0;
    }
    length_ = bounds_.back();
    min_cap_ = RangeMin(caps_);
    least_cap_ = min_cap_(0, caps_.size() - 1);
    double top = 0.0;
    for (double c : caps_) top = std::max(top, c);
    slack_v_ = tolerances::chain_profile_speed_slack * top;
    // The limits at speed levels (shares of the largest cap, and the look-ahead's band tops: shares
    // of the smallest, so that a change of speed the look-ahead planned under the chain's bands is
    // judged here under bands at least as large), each stretch's at its band that holds up to the
    // level; without bands, one level: every stretch's at its cap.
    if (banded_) {
      for (const double f : tolerances::chain_profile_speed_levels) levels_.push_back(f * top);
      for (const double f : tolerances::plan_acceleration_band_tops) levels_.push_back(f * least_cap_);
      std::sort(levels_.begin(), levels_.end());
      levels_.erase(std::unique(levels_.begin(), levels_.end()), levels_.end());
    }
    levels_.push_back(std::numeric_limits<double>::infinity());
    std::vector<double> acc(stretches.size()), jerk(stretches.size());
    for (const double level : levels_) {
      for (std::size_t k = 0; k < stretches.size(); ++k) {
        const Lim l = stretch_limits(stretches[k], level);
        acc[k] = l.a;
        jerk[k] = l.j;
      }
      min_acc_.emplace_back(acc);
      min_jerk_.emplace_back(jerk);
    }
    junction_speed_.assign(caps_.size() + 1, 0.0);
    junction_speed_[caps_.size()] = v1_;
    for (std::size_t m = caps_.size() - 1; m >= 1; --m)
      junction_speed_[m] = std::min(caps_[m - 1], caps_[m]);
    if (cautious)  // backwards: slow enough to brake to the next junction's speed within the stretch
      for (std::size_t m = caps_.size() - 1; m >= 1; --m)
        junction_speed_[m] = std::min(junction_speed_[m], reachable_velocity(junction_speed_[m + 1],
                                                                             bounds_[m + 1] - bounds_[m],
                                                                             {top, min_acc_.back()[m], min_jerk_.back()[m]}));
  }

  // A stretch's limits at speeds up to v [mm/s]: of its lowest speed band that holds there, else
  // at its cap.
  [[nodiscard]] Lim stretch_limits(const CapStretch& c, double v) const {
    for (int k = 0; k + 1 < c.bands.n; ++k)  // (the last band is the cap's)
      if (c.bands.top_mm_s[static_cast<std::size_t>(k)] >= v) return band_limits(c, k);
    return band_limits(c, -1);
  }

  // The limits of a stretch's speed band k (-1: at its cap), each at most the chain's.
  [[nodiscard]] Lim band_limits(const CapStretch& c, int k) const {
    const Lim l = k < 0 ? Lim{c.max_acceleration, c.max_jerk}
                        : Lim{c.bands.acceleration[static_cast<std::size_t>(k)], c.bands.max_jerk};
    return {std::min(limits_.max_acceleration, l.a), std::min(limits_.max_jerk, l.j)};
  }

  // The speed level [index] whose limits hold at speeds up to v [mm/s].
  [[nodiscard]] std::size_t level(double v) const {
    return static_cast<std::size_t>(std::lower_bound(levels_.begin(), levels_.end() - 1, v - slack_v_) -
                                    levels_.begin());
  }

  // Smallest cap over the open interval (a, b) of distance [mm].
  [[nodiscard]] double min_cap(double a, double b) const {
    const std::size_t first = stretch_at(a);
    return min_cap_(first, std::max(first, stretch_ending_at(b)));
  }

  // Smallest limits over the stretches that [a, b] [mm] touches, at speeds up to v [mm/s].
  [[nodiscard]] Lim limits_over(double a, double b, double v) const {
    return limits_of(stretch_at(a), stretch_at(b), v);
  }

  // Smallest limits over stretches first .. last at speeds up to v [mm/s].
  [[nodiscard]] Lim limits_of(std::size_t first, std::size_t last, double v) const {
    const std::size_t k = level(v);
    return {min_acc_[k](first, last), min_jerk_[k](first, last)};
  }

  // The stretch containing distance s (the later one at a boundary).
  [[nodiscard]] std::size_t stretch_at(double s) const {
    const auto it = std::upper_bound(bounds_.begin() + 1, bounds_.end() - 1, s);
    return static_cast<std::size_t>(it - (bounds_.begin() + 1));
  }

  // The speed [mm/s] at junction m (1 <= m < caps_.size()): at most both caps; at the end
  // (m = caps_.size()), exactly v1.
  [[nodiscard]] double junction_speed(std::size_t m) const { return junction_speed_[m]; }

  // Bringing x's acceleration to zero at the smallest jerk of the stretches the easing runs
  // through.
  [[nodiscard]] Ease ease_from(const Kin& x) const {
    double j = min_jerk_[level(x.v)][stretch_at(x.s)];
    Ease e = ease(x, j);
    for (int it = 0; it < tolerances::chain_profile_ease_rounds && e.duration_s > 0.0; ++it) {
      const double lower = limits_over(x.s, x.s + std::max(0.0, e.distance_mm), std::max(x.v, e.v_end)).j;
      if (!(lower < j)) break;
      j = lower;
      e = ease(x, j);
    }
    return e;
  }

  // The junction after `from` (or the end) with the least room from x, and that room [mm].
  [[nodiscard]] std::pair<std::size_t, double> tightest_after(const Kin& x, const Ease& e, std::size_t from) const {
    const std::size_t n = caps_.size(), first = stretch_at(x.s);
    const double end_room = room(x, e, n);
    std::size_t inner = n;
    double inner_room = std::numeric_limits<double>::infinity();
    for (std::size_t m = std::max(first, from) + 1; m < n; ++m) {
      const double w = junction_speed(m);
      if (e.v_end <= w) continue;  // (no braking for it)
      // (where even the room at the smallest limits up to it is not the least, the junction is not)
      if (room_at_least(x, e, m, w) >= std::min(inner_room, end_room)) continue;
      const double r = room(x, e, m);
      if (r < inner_room) {
        inner_room = r;
        inner = m;
      }
    }
    if (inner_room < end_room) return {inner, inner_room};
    return {n, end_room};
  }

  // Room left [mm] for the manoeuvre from x towards junction m (speed at most junction_speed(m)
  // there) or the end (speed exactly v1), its S-curve at the smallest limits of the stretches it
  // runs through (under their bands: change_distance); negative if it no longer fits; +infinity if
  // that junction does not ask for it. `sign_only`: only whether it is negative counts (a room of
  // at least zero at the limits of the top speed is given as it is).
  [[nodiscard]] double room(const Kin& x, const Ease& e, std::size_t m, bool sign_only = false) const {
    const bool end = m == caps_.size();
    const double w = landing_speed(m, e.v_end), dist = bounds_[m] - x.s, from = x.s + e.distance_mm;
    const double enough = sign_only ? dist - e.distance_mm : 0.0;
    if (e.v_end > w)
      return dist - e.distance_mm - change_distance(from, bounds_[m], e.v_end, w, enough);
    if (e.v_end < w) {
      // speeding up to it: only once no smaller cap lies between (that one binds first)
      if (min_cap(x.s, bounds_[m]) + slack_v_ < w) return std::numeric_limits<double>::infinity();
      return dist - e.distance_mm - change_distance(from, bounds_[m], e.v_end, w, enough);
    }
    return end ? dist - e.distance_mm : std::numeric_limits<double>::infinity();
  }

  // The smallest limits over the stretches that one S-curve change of speed from v to w [mm/s]
  // between distances from and to [mm] runs through: braking, it cruises first and brakes at the
  // end; speeding up, it speeds up first and cruises after.
  // (`peak`: the highest speed it may reach, if above both)
  [[nodiscard]] Lim change_limits(double from, double to, double v, double w, double peak = 0.0) const {
    const bool braking = v > w;
    const double top = std::max({v, w, peak});
    const std::size_t k0 = braking ? stretch_ending_at(to) : stretch_at(from), lv = level(top);
    Lim l{min_acc_[lv][k0], min_jerk_[lv][k0]};
    for (int it = 0; it < tolerances::chain_profile_ease_rounds; ++it) {
      const double d = velocity_change_distance(v, w, l.a, l.j);
      const Lim over = braking ? limits_inside(std::max(from, to - d), to, top)
                               : limits_inside(from, std::min(to, from + d), top);
      if (!(over.a < l.a) && !(over.j < l.j)) return l;
      l.take(over.a, over.j);
    }
    return limits_inside(from, to, top);
  }

  // Its distance [mm]: on a chain with speed levels, under the bands of those stretches (more
  // acceleration at the lower speeds of the change), else at their limits at its top speed. (A
  // distance up to `enough` [mm] serves as well as the exact one: where the change at the limits
  // of its top speed is no longer, the bands are not looked at.)
  [[nodiscard]] double change_distance(double from, double to, double v, double w, double enough = 0.0) const {
    const Lim l = change_limits(from, to, v, w);
    const double constant = velocity_change_distance(v, w, l.a, l.j);
    if (!banded_ || constant <= enough) return constant;
    return std::min(constant, banded_change_distance(std::min(v, w), std::max(v, w), change_bands(from, to, v, w, l)));
  }

  // The speed bands of the stretches a change of speed from v to w between distances from and to
  // [mm] runs through (those change_limits found, whose limits at the change's top speed are l):
  // up to each speed level between the change's speeds, the smallest of their limits that hold up
  // to it; up to the top (max(v, w, peak)), l.
  [[nodiscard]] AccelerationBands change_bands(double from, double to, double v, double w, const Lim& l,
                                               double peak = 0.0) const {
    static_assert(std::size(tolerances::chain_profile_speed_levels) + std::size(tolerances::plan_acceleration_band_tops) <
                  AccelerationBands::kMax);
    const bool braking = v > w;
    const double top = std::max({v, w, peak}), low = std::min(v, w);
    // (the range change_limits settled on: the stretches within its distance at l)
    const double d = velocity_change_distance(v, w, l.a, l.j);
    const double a = braking ? std::max(from, to - d) : from, b = braking ? to : std::min(to, from + d);
    const std::size_t last = stretch_ending_at(b), first = std::min(stretch_at(a), last);
    AccelerationBands bands;
    bands.max_jerk = l.j;
    // Each band takes the smallest limits of the stretches the change may pass at its speeds only.
    // A monotone change (no peak above both ends) runs at most at each band's acceleration while
    // in it, so it runs faster than `below` only farther from its slow end than the sum over the
    // bands below of (top^2 - bottom^2) / (2 acceleration) (`reach`): a braking into tight
    // stretches passes them slowly (runs_above), and the bands above them may leave more
    // acceleration than those below. A change with a peak: every stretch it runs through, at every
    // band, which leaves the accelerations not rising with the speed.
    const bool monotone = !(peak > std::max(v, w));
    double below = low;   // the lower edge of the band being added [mm/s]
    double reach = 0.0;   // [mm] the least distance from the slow end at which it runs above `below`
    const auto runs_above = [&]() -> std::pair<std::size_t, std::size_t> {
      if (!monotone || !(reach > 0.0)) return {first, last};
      if (braking) return {first, std::max(first, std::min(last, stretch_ending_at(to - reach)))};
      return {std::min(last, std::max(first, stretch_at(from + reach))), last};
    };
    const auto add_band = [&](std::size_t k, double top_mm_s) {
      const auto [f, g] = runs_above();
      const double acc = std::max(min_acc_[k](f, g), l.a);
      bands.top_mm_s[static_cast<std::size_t>(bands.n)] = top_mm_s;
      bands.acceleration[static_cast<std::size_t>(bands.n)] = acc;
      ++bands.n;
      bands.max_jerk = std::min(bands.max_jerk, min_jerk_[k](f, g));
      if (acc > 0.0 && std::isfinite(acc)) reach += (top_mm_s * top_mm_s - below * below) / (2.0 * acc);
      below = top_mm_s;
    };
    for (std::size_t k = 0; k + 1 < levels_.size(); ++k) {
      if (!(levels_[k] > low) || !(levels_[k] < top - slack_v_)) continue;
      add_band(k, levels_[k]);
    }
    add_band(level(top), top);
    return bands;
  }

  // Smallest limits over the stretches that the interval (a, b) [mm] runs through, at speeds up to
  // v [mm/s].
  [[nodiscard]] Lim limits_inside(double a, double b, double v) const {
    const std::size_t last = stretch_ending_at(b);
    return limits_of(std::min(stretch_at(a), last), last, v);
  }

  // The stretch whose part up to distance s contains it (the earlier one at a junction).
  [[nodiscard]] std::size_t stretch_ending_at(double s) const {
    const auto it = std::lower_bound(bounds_.begin() + 1, bounds_.end() - 1, s);
    return static_cast<std::size_t>(it - (bounds_.begin() + 1));
  }

  // The speed [mm/s] a manoeuvre arriving at junction m from speed v lands at: the junction's
  // speed where v is above it; at the end, exactly v1.
  [[nodiscard]] double landing_speed(std::size_t m, double v) const {
    return m == caps_.size() ? v1_ : std::min(v, junction_speed_[m]);
  }

  // True if x's acceleration may be eased to zero: it does not run, with more acceleration than
  // allowed there, into a stretch of a smaller acceleration limit.
  [[nodiscard]] bool ease_fits(const Kin& x, const Ease& e) const {
    const std::size_t first = stretch_at(x.s);
    const RangeMin& acc = min_acc_[level(std::max(x.v, e.v_end))];
    if (std::abs(x.a) > acc[first] * (1.0 + 1e-9)) return false;
    for (std::size_t k = first + 1; k < caps_.size() && bounds_[k] < x.s + e.distance_mm; ++k)
      if (std::abs(x.a) > acc[k]) return false;
    return true;
  }

  // True if from x every junction ahead and the end can still be met.
  [[nodiscard]] bool safe(const Kin& x) const {
    const Ease e = ease_from(x);
    if (e.v_end < 0.0) return false;
    if (std::max(x.v, e.v_end) > min_cap(x.s, x.s + e.distance_mm) + slack_v_) return false;
    if (!ease_fits(x, e)) return false;
    const std::size_t end = caps_.size(), first = stretch_at(x.s);
    const Lim least = limits_of(first, end - 1, e.v_end);
    // (beyond this, even at the smallest limits ahead, braking to a stop fits before the junction)
    const double reach = e.distance_mm + 2.0 * velocity_change_distance(e.v_end, 0.0, least.a, least.j);
    for (std::size_t m = first + 1; m < end && bounds_[m] - x.s <= reach; ++m) {
      const double w = junction_speed(m);
      if (e.v_end <= w) continue;
      // (braking at the smallest limits up to it fits: no need to find the stretches it runs through)
      if (room_at_least(x, e, m, w) >= 0.0) continue;
      if (room(x, e, m, true) < 0.0) return false;
    }
    // the end, which must be met exactly, is always looked at: speeding up to it may take longer
    // than stopping
    if (!(e.v_end < v1_) && room_at_least(x, e, end, v1_) >= 0.0) return true;
    return room(x, e, end, true) >= 0.0;
  }

  // A lower bound on the room [mm] for braking from x to speed w at junction m: at the smallest
  // limits of all the stretches from x to it (room() finds those the braking runs through).
  [[nodiscard]] double room_at_least(const Kin& x, const Ease& e, std::size_t m, double w) const {
    const Lim upto = limits_of(stretch_at(x.s), m - 1, std::max(e.v_end, w));
    return bounds_[m] - x.s - e.distance_mm - velocity_change_distance(e.v_end, w, upto.a, upto.j);
  }

  // The profile, or none if the steps ran out or the check failed.
  [[nodiscard]] std::optional<trajectory::PathProfile> plan(double dt, double time_bound_s) {
    std::vector<ProfilePhase> phases;
    Kin x{0.0, v0_, 0.0};
    double t = 0.0;
    const auto max_steps =
        static_cast<std::size_t>(tolerances::chain_profile_max_steps_per_flat * time_bound_s / dt) + 64;
    std::size_t steps = 0;
    for (;;) {
      if (++steps > max_steps) return std::nullopt;
      bool moved = false;
      for (const double want : {1.0, 0.0, -1.0}) {
        // the limits of the stretch it is in, then of all the stretches the step runs through
        const std::size_t here = stretch_at(x.s), lv = level(x.v);
        Lim l{min_acc_[lv][here], min_jerk_[lv][here]};
        Kin y;
        double j = 0.0;
        bool within = false;
        for (int round = 0; round < 3 && !within; ++round) {
          if (std::abs(x.a) > l.a) break;
          j = std::clamp(want * l.j, (-l.a - x.a) / dt, (l.a - x.a) / dt);
          y = advance(x, j, dt);
          if (!(y.s > x.s)) break;
          const Lim span = limits_over(x.s, y.s, speed_range(x, j, dt, y).hi);
          within = !(std::abs(x.a) > span.a) && !(std::abs(y.a) > span.a * (1.0 + 1e-12)) &&
                   !(std::abs(j) > span.j * (1.0 + 1e-12));
          l = span;
        }
        if (!within || !(y.s < length_) || !(y.s > x.s)) continue;
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
      const Ease e = ease_from(x);
      const std::size_t from = stretch_at(x.s);
      std::size_t bind = tightest_after(x, e, from).first;
      while (bind < caps_.size()) {
        const Kin land{bounds_[bind], landing_speed(bind, e.v_end), 0.0};
        const auto [next, r] = tightest_after(land, ease_from(land), bind);
        if (!(r < 0.0)) break;
        bind = next;
      }
      if (e.duration_s > 0.0) {
        phases.push_back({t, {x.s, x.v, x.a, e.jerk}, e.jerk});
        t += e.duration_s;
        x = advance(x, e.jerk, e.duration_s);
        x.a = 0.0;
      }
      // One S-curve to the junction, at the smallest limits from x to it, or under their speed
      // bands (as it was judged: room()); where it would pass a junction before it too fast, it
      // aims at that one instead.
      trajectory::PathProfile c;
      double w = 0.0;
      for (;;) {
        w = landing_speed(bind, x.v);
        const double peak = std::max({x.v, w, x.v > slack_v_ ? 0.0 : least_cap_});
        const Lim l = change_limits(x.s, bounds_[bind], x.v, w, peak);
        const double dist = bounds_[bind] - x.s;
        if (!(dist >= 0.0) || x.v < 0.0) return std::nullopt;
        const PathLimits pl{peak, l.a, l.j};
        c = trajectory::PathProfile(plan_scurve(dist, x.v, w, pl));
        // (under the bands where that is faster, or where only that reaches w)
        if (banded_)
          if (std::optional<trajectory::PathProfile> q =
                  plan_banded_profile(dist, x.v, w, change_bands(x.s, bounds_[bind], x.v, w, l, peak));
              q && (q->duration() < c.duration() || !(std::abs(c.end_velocity() - w) <= slack_v_)))
            c = std::move(*q);
        if (!(std::abs(c.end_velocity() - w) <= slack_v_)) return std::nullopt;
        std::size_t over = bind;
        for (std::size_t m = stretch_at(x.s) + 1; m < bind && over == bind; ++m)
          if (c.sample(c.time_at(bounds_[m] - x.s)).v > junction_speed(m) + slack_v_) over = m;
        if (over == bind) break;
        bind = over;
      }
      const bool end = bind == caps_.size();
      const double target = bounds_[bind];
      append_by_level(c, t, x.s, phases);
      t += c.duration();
      x = {target, w, 0.0};
      if (end) break;
    }
    if (!fits(phases, t)) return std::nullopt;
    return trajectory::PathProfile(std::move(phases), t, {length_, v1_, 0.0, 0.0});
  }

  // Appends a manoeuvre's phases, shifted by t0_s [s] and s0_mm [mm], each cut where its speed
  // passes a speed level: a banded change's ramp runs through several bands, and fits() judges
  // each phase by the band of its highest speed.
  void append_by_level(const trajectory::PathProfile& c, double t0_s, double s0_mm,
                       std::vector<ProfilePhase>& out) const {
    std::vector<ProfilePhase> own;
    c.append_phases_to(t0_s, s0_mm, own);
    for (std::size_t k = 0; k < own.size(); ++k) {
      const ProfilePhase& p = own[k];
      out.push_back(p);
      const double dt = (k + 1 < own.size() ? own[k + 1].t0_s : t0_s + c.duration()) - p.t0_s;
      if (!(dt > 0.0) || (p.jerk == 0.0 && p.start.a == 0.0)) continue;
      // (the speed is monotone within a phase of a change: its acceleration keeps its sign)
      const Kin x{p.start.s, p.start.v, p.start.a}, y = advance(x, p.jerk, dt);
      const bool rising = y.v > x.v;
      const std::size_t from = out.size();
      for (std::size_t m = 0; m + 1 < levels_.size(); ++m) {
        const double level = levels_[m];
        if (!(level > std::min(x.v, y.v) && level < std::max(x.v, y.v))) continue;
        const double tau = first_time(dt, [&](double t) { return (advance(x, p.jerk, t).v < level) == rising; });
        const Kin z = advance(x, p.jerk, tau);
        out.push_back({p.t0_s + tau, {z.s, z.v, z.a, p.jerk}, p.jerk});
      }
      std::sort(out.begin() + static_cast<std::ptrdiff_t>(from), out.end(),
                [](const ProfilePhase& a, const ProfilePhase& b) { return a.t0_s < b.t0_s; });
    }
  }

  // Every phase within the cap, acceleration and jerk limits of each stretch it runs through, over
  // the part of it inside that stretch (a phase that ends or starts on a junction counts only to
  // the stretches it runs inside; a braking phase may cross into a lower cap once its speed is
  // below it), the speed never negative.
  [[nodiscard]] bool fits(const std::vector<ProfilePhase>& phases, double duration_s) const {
    const double ds = tolerances::chain_profile_boundary_mm;
    // (within the limits at its cap or of a band that holds up to the part's highest speed)
    const auto within = [&](std::size_t m, const Kin& a, const Kin& b, double jerk, double v_hi) {
      const auto in = [&](const Lim& l) {
        return !(std::abs(a.a) > l.a * (1.0 + 1e-9)) && !(std::abs(b.a) > l.a * (1.0 + 1e-9)) &&
               !(std::abs(jerk) > l.j * (1.0 + 1e-9));
      };
      const CapStretch& c = stretches_[m];
      if (in(band_limits(c, -1))) return true;
      for (int k = 0; k + 1 < c.bands.n; ++k)
        if (c.bands.top_mm_s[static_cast<std::size_t>(k)] + slack_v_ >= v_hi && in(band_limits(c, k))) return true;
      return false;
    };
    for (std::size_t k = 0; k < phases.size(); ++k) {
      const ProfilePhase& p = phases[k];
      const double dt = (k + 1 < phases.size() ? phases[k + 1].t0_s : duration_s) - p.t0_s;
      const Kin x{p.start.s, p.start.v, p.start.a};
      const Kin y = advance(x, p.jerk, dt);
      const SpeedRange r = speed_range(x, p.jerk, dt, y);
      if (r.lo < -slack_v_) return false;
      const double lo = std::min(x.s + ds, 0.5 * (x.s + y.s)), hi = std::max(y.s - ds, 0.5 * (x.s + y.s));
      const std::size_t first = stretch_at(lo), last = stretch_at(hi);
      if (first == last) {
        if (r.hi > caps_[first] + slack_v_ || !within(first, x, y, p.jerk, r.hi)) return false;
        continue;
      }
      // Crossing junctions: each part against its own stretch's cap and limits.
      double t_a = 0.0;
      for (std::size_t m = first; m <= last; ++m) {
        const double t_b = m == last ? dt : crossing_time(x, p.jerk, dt, bounds_[m + 1]);
        const Kin a = advance(x, p.jerk, t_a), b = advance(x, p.jerk, t_b);
        const double v_hi = speed_range(a, p.jerk, t_b - t_a, b).hi;
        if (v_hi > caps_[m] + slack_v_ || !within(m, a, b, p.jerk, v_hi)) return false;
        t_a = t_b;
      }
    }
    return true;
  }

  // The first time [s] within [0, dt] at which `before(t)` turns false (it is true before that
  // time and false after), by bisection to the last bit.
  template <class Before>
  [[nodiscard]] static double first_time(double dt, Before before) {
    double lo = 0.0, hi = dt;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (before(mid) ? lo : hi) = mid;
    }
    return hi;
  }

  // The time [s] within [0, dt] at which a phase of jerk j from x reaches distance s_mm (its
  // distance does not fall: the speed is not negative).
  [[nodiscard]] static double crossing_time(const Kin& x, double j, double dt, double s_mm) {
    return first_time(dt, [&](double t) { return advance(x, j, t).s < s_mm; });
  }

 private:
  double v0_, v1_;
  std::span<const CapStretch> stretches_;
  PathLimits limits_;  // the chain's (no stretch's are larger)
  std::vector<double> bounds_, caps_, junction_speed_;  // junction_speed_[m]: at bounds_[m], m >= 1
  std::vector<double> levels_;  // speed levels [mm/s], ascending, the last infinite
  RangeMin min_cap_;  // over ranges of stretches
  // [level]: each stretch's limits at speeds up to the level, and their minima over ranges
  std::vector<RangeMin> min_acc_, min_jerk_;
  double length_ = 0.0, slack_v_ = 0.0;
  double least_cap_ = 0.0;  // the smallest cap of any stretch [mm/s]
  bool banded_ = false;  // a stretch has speed bands: the limits are looked up by speed level
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
