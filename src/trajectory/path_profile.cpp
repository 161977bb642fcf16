#include <algorithm>
#include <cmath>
#include <limits>

#include <kontur/geometry/bracket.hpp>
#include <kontur/trajectory/path_profile.hpp>
#include <kontur/tolerances.hpp>

namespace kontur::trajectory {

void append_phases(const ScurveProfile& s, double t0_s, double s0_mm, std::vector<ProfilePhase>& out) {
  double t = 0.0;
  PathState at = s.sample(0.0);
  for (int k = 0; k < 7; ++k) {
    const double t_end = s.phase_end_time(k);
    if (t_end > t) {
      PathState start = at;
      start.s += s0_mm;
      out.push_back({t0_s + t, start, s.phase_jerk(k)});
      t = t_end;
      at = s.sample_phase_end(k);
    }
  }
}

void PathProfile::append_phases_to(double t0_s, double s0_mm, std::vector<ProfilePhase>& out) const {
  if (!data_) return;
  for (const ProfilePhase& p : data_->phases) {
    ProfilePhase q = p;
    q.t0_s += t0_s;
    q.start.s += s0_mm;
    out.push_back(q);
  }
}

PathProfile::PathProfile(const ScurveProfile& s) {
  std::vector<ProfilePhase> phases;
  append_phases(s, 0.0, 0.0, phases);
  *this = PathProfile(std::move(phases), s.duration(), {s.distance(), s.end_velocity(), 0.0, 0.0});
}

PathProfile::PathProfile(std::vector<ProfilePhase> phases, double duration_s, const PathState& end) {
  auto d = std::make_shared<Data>();
  d->phases = std::move(phases);
  if (d->phases.empty()) d->phases.push_back({0.0, end, 0.0});
  d->duration_s = duration_s;
  d->end = end;
  d->end.a = 0.0;
  d->end.j = 0.0;
  {
    const ProfilePhase& p = d->phases.back();
    const double tau = std::max(0.0, duration_s - p.t0_s);
    const double natural = p.start.s + p.start.v * tau + 0.5 * p.start.a * tau * tau + p.jerk * tau * tau * tau / 6.0;
    d->s0 = d->phases.front().start.s;
    const double want = d->end.s - d->s0, got = natural - d->s0;
    // (a difference of a few units in the last place is left: the profile then samples exactly as
    // the S-curve it was made from)
    const double miss = want > 0.0 && got > 0.0 ? std::abs(want / got - 1.0) : 0.0;
    if (miss > 64.0 * std::numeric_limits<double>::epsilon() && miss <= tolerances::profile_end_rescale_relative)
      d->scale = want / got;
  }
  data_ = std::move(d);
}

double PathProfile::start_velocity() const noexcept { return data_ ? data_->phases.front().start.v : 0.0; }

namespace {

// The state at time t [s] in phase p (t in [p.t0_s, duration)), as sample() gives it.
PathState state_in_phase(const ProfilePhase& p, double t, double s0, double scale, double end_s) noexcept {
  const double tau = t - p.t0_s, j = p.jerk;
  PathState out;
  out.j = j;
  out.a = p.start.a + j * tau;
  out.v = p.start.v + p.start.a * tau + 0.5 * j * tau * tau;
  out.s = p.start.s + p.start.v * tau + 0.5 * p.start.a * tau * tau + j * tau * tau * tau / 6.0;
  if (scale != 1.0) {
    out.s = s0 + (out.s - s0) * scale;
    out.v *= scale;
    out.a *= scale;
    out.j *= scale;
  }
  // Rounding must not move past the end.
  out.s = std::min(out.s, end_s);
  out.v = std::max(out.v, 0.0);
  return out;
}

}  // namespace

PathState PathProfile::sample(double t) const noexcept {
  if (!data_) return {};
  const Data& d = *data_;
  if (!(t > 0.0)) return d.phases.front().start;
  if (t >= d.duration_s) return d.end;
  // The last phase starting at or before t.
  const auto it = std::upper_bound(d.phases.begin(), d.phases.end(), t,
                                   [](double x, const ProfilePhase& p) { return x < p.t0_s; });
  return state_in_phase(*(it == d.phases.begin() ? it : it - 1), t, d.s0, d.scale, d.end.s);
}

double PathProfile::time_at(double s_mm) const noexcept {
  if (!data_) return 0.0;
  const Data& d = *data_;
  // The bisection of first_time_covering on sample(t).s >= s_mm, narrowed first to the phase in
  // which s_mm is reached (its start does not cover s_mm, the next phase's start does), then on
  // that phase's cubic by regula falsi: the same first time, in a few evaluations.
  const auto short_of = [&](const ProfilePhase& q) {  // the phase's start does not cover s_mm
    return q.t0_s >= d.duration_s ? d.end.s < s_mm : state_in_phase(q, q.t0_s, d.s0, d.scale, d.end.s).s < s_mm;
  };
  // the first phase after the first one whose start covers s_mm (end: none), and the one before
  const auto next = std::partition_point(d.phases.begin() + 1, d.phases.end(), short_of);
  const ProfilePhase& p = *(next - 1);
  const double lo = next - 1 == d.phases.begin() ? 0.0 : p.t0_s;
  const double hi = next == d.phases.end() ? d.duration_s : std::min(next->t0_s, d.duration_s);
  const auto covered = [&](double t) {
    return t >= d.duration_s ? d.end.s : state_in_phase(p, t, d.s0, d.scale, d.end.s).s;
  };
  // "not yet covered" as an excess <= 0 (covered exactly: the least positive excess)
  const auto excess = [&](double t) {
    const double e = covered(t) - s_mm;
    return e < 0.0 ? e : std::max(e, std::numeric_limits<double>::denorm_min());
  };
  return narrow_and_bisect(lo, hi, covered(lo) - s_mm, covered(hi) - s_mm, excess).hi;
}

}  // namespace kontur::trajectory
