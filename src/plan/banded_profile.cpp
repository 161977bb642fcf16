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
struct Step {
  double tau_s = 0.0;  // [s]
  double jerk = 0.0;   // [mm/s^3]
};

// The steps of the fastest change from va up to vb under the bands (see the header): at most a
// ramp up, then a flat and a ramp down per band.
struct Change {
  std::array<Step, 2 * AccelerationBands::kMax + 2> steps{};
  int n = 0;
  double duration_s = 0.0;
  double distance_mm = 0.0;
  void push(double tau, double jerk) {
    if (!(tau > 0.0)) return;
    steps[static_cast<std::size_t>(n++)] = {tau, jerk};
    duration_s += tau;
  }
};

Change change_up(double va, double vb, const AccelerationBands& b) {
  Change c;
  if (!(vb > va)) return c;
  const double jm = b.max_jerk;
  // Where the acceleration must have come down to: at each band's top inside (va, vb) to the next
  // band's acceleration, at vb to zero.
  struct Threshold {
    double u = 0.0, a = 0.0;  // [mm/s], [mm/s^2]
  };
  std::array<Threshold, AccelerationBands::kMax + 1> th{};
  int nt = 0;
  for (int k = 0; k + 1 < b.n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (b.top_mm_s[kk] > va && b.top_mm_s[kk] < vb) th[static_cast<std::size_t>(nt++)] = {b.top_mm_s[kk], b.acceleration[kk + 1]};
  }
  th[static_cast<std::size_t>(nt++)] = {vb, 0.0};
  // The ramp up from zero acceleration meets the bound first: on a band's flat (at speed
  // va + a^2 / 2J inside that band) or on a ramp down towards a threshold (a^2 = a_m^2 + 2J (u_m - v)
  // with v = va + a^2 / 2J, before u_m).
  double a = kInf;
  for (int m = 0; m < nt; ++m) {
    const Threshold& t = th[static_cast<std::size_t>(m)];
    const double cand = std::sqrt(0.5 * (t.a * t.a + 2.0 * jm * (t.u - va)));
    if (va + cand * cand / (2.0 * jm) <= t.u) a = std::min(a, cand);
  }
  for (int k = 0; k < b.n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double alpha = b.acceleration[kk], lower = k == 0 ? -kInf : b.top_mm_s[kk - 1];
    const double vc = va + alpha * alpha / (2.0 * jm);
    if (vc > lower && (vc <= b.top_mm_s[kk] || k + 1 == b.n)) a = std::min(a, alpha);
  }
  c.push(a / jm, jm);
  double v = va + a * a / (2.0 * jm);
  // Along the bound: flat at the band's acceleration until the ramp down towards the binding
  // threshold (the least a_m^2 + 2J u_m ahead) begins, then that ramp, which lands on it (the flat
  // is empty where the ramp up met the bound on that ramp). The flat's end speed is computed as
  // u_m - (a^2 - a_m^2) / 2J, free of the cancellation of C - 2J v.
  int first = 0;  // the thresholds the ramp passed are behind
  while (first + 1 < nt && th[static_cast<std::size_t>(first)].u <= v) ++first;
  for (int guard = 0; guard <= AccelerationBands::kMax + 1; ++guard) {
    int m = nt - 1;
    double big_c = kInf;
    for (int i = first; i < nt; ++i) {
      const Threshold& t = th[static_cast<std::size_t>(i)];
      const double ci = t.a * t.a + 2.0 * jm * t.u;
      if (ci < big_c) {
        big_c = ci;
        m = i;
      }
    }
    const Threshold& t = th[static_cast<std::size_t>(m)];
    const double v_end = std::max(v, t.u - (a * a - t.a * t.a) / (2.0 * jm));
    if (a > 0.0) c.push((v_end - v) / a, 0.0);
    c.push((a - t.a) / jm, -jm);
    v = t.u;
    a = t.a;
    first = m + 1;
    if (m == nt - 1) break;
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
    if (k > 0 && !(b.top_mm_s[kk] > b.top_mm_s[kk - 1] && b.acceleration[kk] <= b.acceleration[kk - 1])) return false;
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
