#include <algorithm>
#include <cmath>
#include <kontur/plan/banded_profile.hpp>
#include <kontur/tolerances.hpp>
#include <limits>
#include <vector>

#include "bisection.hpp"

namespace kontur::plan {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A state after a constant-jerk step of duration tau [s] from x.
trajectory::PathState advance(const trajectory::PathState& x, double tau, double jerk) noexcept {
  return {x.s + (x.v * tau + 0.5 * x.a * tau * tau + jerk * tau * tau * tau / 6.0),
          x.v + (x.a * tau + 0.5 * jerk * tau * tau), x.a + jerk * tau, jerk};
}

// One constant-jerk step of a change of speed.
// (no default values: a change's array of them is set only as far as it is used)
struct Step {
  double tau_s;  // [s]
  double jerk;   // [mm/s^3]
};

// The steps of the fastest change from va up to vb under the bands (see the header): at most a
// ramp up, a flat and a ramp down per band (consecutive steps of the same jerk merged).
struct Change {
  std::array<Step, 3 * AccelerationBands::kMax + 2> steps;  // (the first n are set)
  int n = 0;
  double duration_s = 0.0;
  double distance_mm = 0.0;
  void push(double tau, double jerk) {
    if (!(tau > 0.0)) return;
    duration_s += tau;
    if (n > 0 && steps[static_cast<std::size_t>(n - 1)].jerk == jerk) {
      steps[static_cast<std::size_t>(n - 1)].tau_s += tau;
      return;
    }
    steps[static_cast<std::size_t>(n++)] = {tau, jerk};
  }
};

Change change_up(double va, double vb, const AccelerationBands& b) {
  Change c;
  if (!(vb > va)) return c;
  const double jm = b.max_jerk, two_j = 2.0 * jm;
  // In the plane of the speed v and the squared acceleration g = a^2 the jerk is half the slope
  // (j = a da/dv = g'/2): the jerk bound is |g'| <= 2J, and the fastest change (t = integral of
  // dv / a) takes the largest g everywhere: the least of the bound alpha(u)^2 + 2J |v - u| over
  // every speed u, with g = 0 at va and vb. The bands inside (va, vb) split it at edges
  // e_0 = va < e_1 < ... < e_m = vb; band i (between e_i and e_i+1) has the bound alpha_i.
  // (arrays of which the first m (+1) are set)
  std::array<double, AccelerationBands::kMax + 1> e;
  std::array<double, AccelerationBands::kMax> alpha, a2;
  int m = 0;
  e[0] = va;
  for (int k = 0; k < b.n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double hi = k + 1 == b.n ? kInf : b.top_mm_s[kk];
    const double lo = std::max(va, k == 0 ? -kInf : b.top_mm_s[kk - 1]);
    const double end = std::min(vb, hi);
    if (!(end > lo)) continue;
    alpha[static_cast<std::size_t>(m)] = b.acceleration[kk];
    a2[static_cast<std::size_t>(m)] = b.acceleration[kk] * b.acceleration[kk];
    e[static_cast<std::size_t>(++m)] = end;
    if (!(end < vb)) break;
  }
  // The least over the speeds at and left of each edge (left[i]) and at and right of it (right[i]).
  std::array<double, AccelerationBands::kMax + 1> left, right;
  const auto mi = static_cast<std::size_t>(m);
  left[0] = 0.0;
  for (std::size_t i = 0; i < mi; ++i) left[i + 1] = std::min(left[i] + two_j * (e[i + 1] - e[i]), a2[i]);
  right[mi] = 0.0;
  for (std::size_t i = mi; i-- > 0;) right[i] = std::min(right[i + 1] + two_j * (e[i + 1] - e[i]), a2[i]);
  for (std::size_t i = 0; i < mi; ++i) {
    // Inside band i: g(v) = min(l0 + 2J (v - e_i), alpha_i^2, r1 + 2J (e_i+1 - v)): a rise at +J
    // up to the flat (at v_r), the flat, and a fall at -J from it (at v_f); where the rise and the
    // fall meet below the flat (v_r > v_f), at v_m, no flat.
    const double e0 = e[i], e1 = e[i + 1];
    const double l0 = std::min(left[i], a2[i]), r1 = std::min(right[i + 1], a2[i]);
    const double v_r = e0 + (a2[i] - l0) / two_j, v_f = e1 - (a2[i] - r1) / two_j;
    if (v_r <= v_f) {
      if (l0 < a2[i]) c.push((alpha[i] - std::sqrt(l0)) / jm, jm);
      c.push((v_f - v_r) / alpha[i], 0.0);
      if (r1 < a2[i]) c.push((alpha[i] - std::sqrt(r1)) / jm, -jm);
      continue;
    }
    const double v_m = 0.5 * (e0 + e1) + (r1 - l0) / (2.0 * two_j);
    if (v_m <= e0) {  // the fall from the band's lower edge
      c.push((std::sqrt(r1 + two_j * (e1 - e0)) - std::sqrt(r1)) / jm, -jm);
    } else if (v_m >= e1) {  // the rise to its upper edge
      c.push((std::sqrt(l0 + two_j * (e1 - e0)) - std::sqrt(l0)) / jm, jm);
    } else {
      const double peak = std::sqrt(l0 + two_j * (v_m - e0));
      c.push((peak - std::sqrt(l0)) / jm, jm);
      c.push((peak - std::sqrt(r1)) / jm, -jm);
    }
  }
  // Its distance, integrated step by step from va.
  trajectory::PathState x{0.0, va, 0.0, 0.0};
  for (int k = 0; k < c.n; ++k) x = advance(x, c.steps[static_cast<std::size_t>(k)].tau_s, c.steps[static_cast<std::size_t>(k)].jerk);
  c.distance_mm = x.s;
  return c;
}

bool valid(const AccelerationBands& b) {
  if (b.n < 1 || b.n > AccelerationBands::kMax || !(b.max_jerk > 0.0) || !std::isfinite(b.max_jerk)) return false;
  for (int k = 0; k < b.n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (!(b.top_mm_s[kk] > 0.0) || !std::isfinite(b.top_mm_s[kk]) || !(b.acceleration[kk] > 0.0) ||
        !std::isfinite(b.acceleration[kk]))
      return false;
    if (k > 0 && !(b.top_mm_s[kk] > b.top_mm_s[kk - 1])) return false;
  }
  return true;
}

}  // namespace

double AccelerationBands::at(double v) const noexcept {
  for (int k = 0; k < n; ++k)
    if (v <= top_mm_s[static_cast<std::size_t>(k)]) return acceleration[static_cast<std::size_t>(k)];
  return n > 0 ? acceleration[static_cast<std::size_t>(n - 1)] : 0.0;
}

namespace {

// The change from va up to vb (at most the last top), or none where the bands are invalid.
std::optional<Change> change_within(double va, double vb, const AccelerationBands& bands) {
  if (!valid(bands)) return std::nullopt;
  return change_up(va, std::min(vb, bands.top_mm_s[static_cast<std::size_t>(bands.n - 1)]), bands);
}

}  // namespace

double banded_change_time(double va, double vb, const AccelerationBands& bands) {
  const std::optional<Change> c = change_within(va, vb, bands);
  return c ? c->duration_s : kInf;
}

double banded_change_distance(double va, double vb, const AccelerationBands& bands) {
  const std::optional<Change> c = change_within(va, vb, bands);
  return c ? c->distance_mm : kInf;
}

double banded_change_time_lost(double va, double vb, const AccelerationBands& bands, double within_mm) {
  std::optional<Change> c = change_within(va, vb, bands);
  if (!c) return kInf;
  const double top = std::min(vb, bands.top_mm_s[static_cast<std::size_t>(bands.n - 1)]);
  if (!(top > 0.0)) return c->duration_s;
  if (c->distance_mm <= within_mm) return std::max(0.0, c->duration_s - c->distance_mm / top);
  // The change does not fit: it runs the whole distance, up to the speed it reaches there.
  c = change_within(va, banded_reachable_velocity(va, within_mm, bands), bands);
  return c ? std::max(0.0, c->duration_s - within_mm / top) : kInf;
}

double banded_reachable_velocity(double v_from, double distance, const AccelerationBands& bands) {
  if (!valid(bands) || !(distance > 0.0)) return v_from;
  const double cap = bands.top_mm_s[static_cast<std::size_t>(bands.n - 1)];
  if (!(v_from < cap)) return v_from;
  const auto excess = [&](double v) { return detail::fit_excess(change_up(v_from, v, bands).distance_mm, distance); };
  const double e_max = excess(cap);
  if (e_max <= 0.0) return cap;
  return narrow_and_bisect(v_from, cap, excess(v_from), e_max, excess).lo;
}

double banded_braking_velocity(double v_after, double distance, const AccelerationBands& bands, double at_least) {
  if (!valid(bands) || !(distance > 0.0)) return std::max(v_after, at_least);
  const double cap = bands.top_mm_s[static_cast<std::size_t>(bands.n - 1)], jm = bands.max_jerk;
  if (!(v_after < cap)) return std::max(v_after, at_least);
  // The longest braking from v to an end speed in [v_after, v].
  const auto worst = [&](double v) {
    double d = change_up(v_after, v, bands).distance_mm;
    const auto at = [&](double w) {
      if (w > v_after && w < v) d = std::max(d, change_up(w, v, bands).distance_mm);
    };
    at(v / 3.0);
    for (int k = 0; k < bands.n; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      at(bands.acceleration[kk] * bands.acceleration[kk] / (2.0 * jm));
      at(bands.top_mm_s[kk]);
    }
    for (int g = 1; g < tolerances::plan_banded_braking_grid; ++g)
      at(v_after + (v - v_after) * g / tolerances::plan_banded_braking_grid);
    return d;
  };
  const auto excess = [&](double v) { return detail::fit_excess(worst(v), distance); };
  // First the speed from which braking to v_after itself fits (one change per step); only where
  // braking to a speed between takes longer from there, the search over every end speed.
  const double direct = banded_reachable_velocity(v_after, distance, bands);
  if (!(direct > at_least)) return std::max(v_after, at_least);
  const double e_direct = excess(direct);
  if (e_direct <= 0.0) return direct;
  return std::max(at_least, narrow_and_bisect(v_after, direct, excess(v_after), e_direct, excess).lo);
}

std::optional<trajectory::PathProfile> plan_banded_profile(double distance, double v0, double v1,
                                                           const AccelerationBands& bands) {
  if (!valid(bands) || !(distance > 0.0) || !(v0 >= 0.0) || !(v1 >= 0.0)) return std::nullopt;
  const double cap = bands.top_mm_s[static_cast<std::size_t>(bands.n - 1)];
  if (v0 > cap || v1 > cap) return std::nullopt;
  auto needed = [&](double vp) { return change_up(v0, vp, bands).distance_mm + change_up(v1, vp, bands).distance_mm; };
  const double floor_v = std::max(v0, v1);
  if (!detail::fits(needed(floor_v), distance)) return std::nullopt;
  const double vp = detail::fits(needed(cap), distance)
                        ? cap
                        : bisect(floor_v, cap, [&](double v) { return detail::fits(needed(v), distance); }).lo;
  if (!(vp > 0.0)) return std::nullopt;
  const Change up = change_up(v0, vp, bands), down = change_up(v1, vp, bands);
  const double cruise = std::max(0.0, distance - up.distance_mm - down.distance_mm) / vp;

  std::vector<trajectory::ProfilePhase> phases;
  phases.reserve(static_cast<std::size_t>(up.n + down.n + 1));
  trajectory::PathState x{0.0, v0, 0.0, 0.0};
  double t = 0.0;
  auto run = [&](double tau, double jerk) {
    phases.push_back({t, {x.s, x.v, x.a, jerk}, jerk});
    x = advance(x, tau, jerk);
    t += tau;
  };
  for (int k = 0; k < up.n; ++k) run(up.steps[static_cast<std::size_t>(k)].tau_s, up.steps[static_cast<std::size_t>(k)].jerk);
  x.v = vp;  // the change ends at vp with zero acceleration (up to rounding)
  x.a = 0.0;
  if (cruise > 0.0) run(cruise, 0.0);
  // The braking: the change up from v1 to vp, mirrored in time (its steps in reverse order, each
  // with the same jerk).
  for (int k = down.n - 1; k >= 0; --k)
    run(down.steps[static_cast<std::size_t>(k)].tau_s, down.steps[static_cast<std::size_t>(k)].jerk);
  return trajectory::PathProfile(std::move(phases), t, {distance, v1, 0.0, 0.0});
}

}  // namespace kontur::plan
