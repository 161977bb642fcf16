#include <kontur/geometry/differential.hpp>
#include <kontur/interpolate/curve_interpolator.hpp>
#include <kontur/plan/lookahead.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace kontur::plan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Highest speed at a move's start from which it can brake, within its length, to v_after or to
// any higher end speed below it (see braking_velocity: monotone in v_after, so rest after the
// window is the most conservative assumption).
double brake_from(double v_after, const MoveConstraint& m) {
  return braking_velocity(v_after, m.length_mm, m.limits);
}

// Junction speeds of a run of moves that starts at v_start and ends at v_end: caps, then a
// backward pass (braking) and a forward pass (acceleration).
std::vector<double> plan_junctions(std::span<const MoveConstraint> moves, double v_start, double v_end) {
  const std::size_t n = moves.size();
  std::vector<double> v(n + 1, 0.0);
  v[0] = v_start;
  v[n] = v_end;
  // Caps at every junction: the junction's own limit and both neighbours' caps.
  for (std::size_t i = 1; i < n; ++i)
    v[i] = std::min({moves[i - 1].max_end_velocity, moves[i - 1].limits.max_velocity, moves[i].limits.max_velocity});
  // Backward: each junction must allow braking to the next within the move between.
  for (std::size_t i = n; i-- > 1;) v[i] = std::min(v[i], brake_from(v[i + 1], moves[i]));
  // Forward: and reaching it from the one before.
  for (std::size_t i = 0; i < n; ++i) v[i + 1] = std::min(v[i + 1], reachable_velocity(v[i], moves[i].length_mm, moves[i].limits));
  return v;
}

}  // namespace

std::vector<double> junction_velocities(std::span<const MoveConstraint> moves) { return plan_junctions(moves, 0.0, 0.0); }

double Lookahead::junction_cap(std::size_t i) const noexcept {
  return std::min({window_[i - 1].max_end_velocity, window_[i - 1].limits.max_velocity, window_[i].limits.max_velocity});
}

double Lookahead::brake_at(std::size_t i, double v_after) const {
  ++evaluations_;
  return brake_from(v_after, window_[i]);
}

bool Lookahead::tail_changed_since_seen() const noexcept {
  if (!tail_dirty_) return false;
  tail_dirty_ = false;
  const MoveConstraint& m = window_.back();
  // back() may have been called without changing anything (a smooth junction).
  return m.length_mm != tail_seen_.length_mm || m.max_end_velocity != tail_seen_.max_end_velocity ||
         m.limits.max_velocity != tail_seen_.limits.max_velocity ||
         m.limits.max_acceleration != tail_seen_.limits.max_acceleration ||
         m.limits.max_jerk != tail_seen_.limits.max_jerk;
}

void Lookahead::update_going_on(std::size_t stop_from) const {
  // going_on_[j] = min(cap_j, brake over move j to going_on_[j + 1]), going_on_[n] = the last
  // move's cap: the same recurrence as the backward pass in plan_junctions. Once a recomputed
  // value equals the cached one at a junction at or below stop_from (below it no junction's own
  // inputs changed), nothing before it changes.
  const std::size_t n = window_.size();
  going_on_.resize(n + 1, 0.0);
  going_on_[n] = window_.back().limits.max_velocity;
  for (std::size_t i = n; i-- > 1;) {
    const double v = std::min(junction_cap(i), brake_at(i, going_on_[i + 1]));
    if (i <= stop_from && v == going_on_[i]) break;
    going_on_[i] = v;
  }
  tail_seen_ = window_.back();
  tail_dirty_ = false;
}

void Lookahead::refresh_tail() const {
  // The last move's limits were lowered: its start junction and the end value change.
  if (tail_changed_since_seen()) {
    rest_valid_ = false;
    update_going_on(window_.size() - 1);
  }
}

void Lookahead::update_rest() const {
  refresh_tail();
  if (rest_valid_) return;
  const std::size_t n = window_.size();
  rest_.assign(n + 1, 0.0);
  std::size_t i = n;
  // From rest after the window until the pass meets the "going on" one (then they agree below).
  for (; i-- > 1;) {
    rest_[i] = std::min(junction_cap(i), brake_at(i, rest_[i + 1]));
    if (rest_[i] == going_on_[i]) break;
  }
  for (; i-- > 1;) rest_[i] = going_on_[i];
  rest_valid_ = true;
}

void Lookahead::push(const MoveConstraint& move) {
  const std::size_t n_old = window_.size();
  const bool tail_changed = n_old >= 1 && tail_changed_since_seen();
  window_.push_back(move);
  rest_valid_ = false;
  if (skip_checks_ > 0) --skip_checks_;
  if (n_old == 0) {
    going_on_.assign(2, 0.0);
    going_on_[1] = move.limits.max_velocity;
    tail_seen_ = move;
    return;
  }
  // The old end junction is recomputed in any case, and the old last move's start junction if
  // its limits were lowered since.
  update_going_on(tail_changed ? n_old - 1 : n_old);
}

bool Lookahead::ready() const {
  if (window_.empty()) return false;
  if (!final_.empty() || finished_ || window_.size() >= max_window) return true;
  if (skip_checks_ > 0) return false;
  // The oldest move is final when its end speed does not depend on what follows the window: the
  // backward pass gives the same speed at junction 1 whether the window ends at rest or the
  // motion goes on at the last move's cap. (Ending every move at zero acceleration makes braking
  // over many short moves far longer than one braking profile, so no distance rule suffices.)
  // Where the rest pass meets the cached "going on" pass, both agree at every junction before:
  // those junctions are final.
  refresh_tail();
  const std::size_t n = window_.size();
  double v = 0.0;  // the rest pass at junction i [mm/s]
  std::size_t cost = 0;
  for (std::size_t i = n; i >= 1; --i) {
    if (i < n) {
      v = std::min(junction_cap(i), brake_at(i, v));
      ++cost;
    }
    if (v == going_on_[i] || (i == 1 && v >= going_on_[1])) {
      for (std::size_t j = 1; j < i; ++j) final_.push_back(going_on_[j]);
      final_.push_back(v);
      break;
    }
  }
  // A test that ran over many moves is not repeated for the next cost / check_defer_share pushes
  // (whether it found final junctions or not): O(check_defer_share) evaluations per push.
  skip_checks_ = cost > check_defer_min ? cost / check_defer_share : 0;
  return !final_.empty();
}

ScurveProfile Lookahead::pop() {
  // From where the previous move ended, to a final junction speed, or to rest after the window.
  double v1 = 0.0;
  if (!final_.empty()) {
    v1 = final_.front();
    final_.pop_front();
  } else {
    update_rest();
    v1 = rest_[1];
  }
  const MoveConstraint& m = window_.front();
  // The forward pass of plan_junctions at junction 1.
  v1 = std::min(v1, reachable_velocity(v_start_, m.length_mm, m.limits));
  ScurveProfile p = plan_scurve(m.length_mm, v_start_, v1, m.limits);
  v_start_ = p.end_velocity();
  window_.pop_front();
  going_on_.pop_front();
  if (rest_valid_) rest_.pop_front();
  if (window_.empty()) {
    going_on_.clear();
    rest_.clear();
    rest_valid_ = false;
    final_.clear();
  }
  return p;
}

void PathGeometry::merge(const PathGeometry& o) noexcept {
  tangent = tangent.cwiseMax(o.tangent);
  curvature = curvature.cwiseMax(o.curvature);
  curvature_rate = curvature_rate.cwiseMax(o.curvature_rate);
  max_kappa = std::max(max_kappa, o.max_kappa);
}

std::pair<Vec3, Vec3> curvature_vector_and_rate(const Derivatives& d) noexcept {
  // With r1 = C', r2 = C'', r3 = C''', q = |r1|^2 and p = r1.r2: K = r2/q - p r1/q^2 = dt/ds, and
  // dK/ds = (dK/du) / |r1| with dK/du = r3/q - 2 p r2/q^2 - ((r3.r1 + r2.r2) r1 + p r2)/q^2
  // + 4 p^2 r1/q^3.
  const Vec3 &r1 = d[1], &r2 = d[2], &r3 = d[3];
  const double q = r1.squaredNorm();
  if (!(q > 0.0)) return {Vec3::Zero(), Vec3::Zero()};
  const double p = r1.dot(r2);
  const Vec3 k = r2 / q - p * r1 / (q * q);
  const Vec3 dk_du = r3 / q - 2.0 * p * r2 / (q * q) - ((r3.dot(r1) + r2.squaredNorm()) * r1 + p * r2) / (q * q) +
                     4.0 * p * p * r1 / (q * q * q);
  return {k, dk_du / std::sqrt(q)};
}

PathGeometry path_geometry(const Curve& c, double u0, double u1, int samples) {
  samples = std::max(samples, 1);
  // Sample until the tangent turns by at most 0.2 rad between samples (a helix of many turns is
  // one span); then a component's peak lies at most about 1 % of its range above the samples.
  for (;;) {
    PathGeometry hi, lo;
    lo.tangent = lo.curvature = lo.curvature_rate = Vec3::Constant(kInf);
    lo.max_kappa = kInf;
    double max_turn = 0.0;
    Vec3 t_before = Vec3::Zero();
    for (int k = 0; k <= samples; ++k) {
      const double u = k == samples ? u1 : u0 + (u1 - u0) * k / samples;
      // The span's own polynomial at its right end (the next span may differ there).
      const Derivatives d = k == samples ? c.derivatives_left(u, 3) : c.derivatives(u, 3);
      const Vec3 t = unit_tangent(d);
      if (t.isZero()) continue;
      if (!t_before.isZero()) max_turn = std::max(max_turn, (t - t_before).norm());
      t_before = t;
      const auto [kv, rate] = curvature_vector_and_rate(d);
      const Vec3 at = t.cwiseAbs(), ak = kv.cwiseAbs(), ar = rate.cwiseAbs();
      hi.tangent = hi.tangent.cwiseMax(at);
      hi.curvature = hi.curvature.cwiseMax(ak);
      hi.curvature_rate = hi.curvature_rate.cwiseMax(ar);
      hi.max_kappa = std::max(hi.max_kappa, kv.norm());
      lo.tangent = lo.tangent.cwiseMin(at);
      lo.curvature = lo.curvature.cwiseMin(ak);
      lo.curvature_rate = lo.curvature_rate.cwiseMin(ar);
      lo.max_kappa = std::min(lo.max_kappa, kv.norm());
    }
    if (max_turn > 0.2 && samples < 4096) {
      samples *= 4;
      continue;
    }
    if (!std::isfinite(lo.max_kappa)) return hi;  // no regular point
    // Constant quantities (a line's tangent, a circle's curvature) are exact; the others are
    // raised by a share of their range between the samples.
    constexpr double m = tolerances::plan_sample_margin;
    hi.tangent = (hi.tangent + m * (hi.tangent - lo.tangent)).cwiseMin(Vec3::Ones());
    hi.curvature += m * (hi.curvature - lo.curvature);
    hi.curvature_rate += m * (hi.curvature_rate - lo.curvature_rate);
    hi.max_kappa += m * (hi.max_kappa - lo.max_kappa);
    return hi;
  }
}

double speed_cap(const PathGeometry& g, double feed_mm_s, const Machine& machine, double centripetal_share) noexcept {
  double v = std::min(feed_mm_s, machine.max_feed_mm_s);
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0) continue;  // rotary axes do not carry the path
    if (g.tangent[i] > 0.0) v = std::min(v, axis.max_velocity / g.tangent[i]);
    if (g.curvature[i] > 0.0) v = std::min(v, std::sqrt(centripetal_share * axis.max_acceleration / g.curvature[i]));
    if (g.curvature_rate[i] > 0.0)
      v = std::min(v, std::cbrt(tolerances::plan_curvature_rate_jerk_share * axis.max_jerk / g.curvature_rate[i]));
  }
  for (char missing : {'X', 'Y', 'Z'}) {
    // An axis the machine does not have cannot move.
    const int i = linear_axis_index(missing);
    if (machine.axis(missing) == nullptr && g.tangent[i] > 1e-12) v = 0.0;
  }
  if (g.max_kappa > 0.0)
    v = std::min(v, chord_limited_feed(1.0 / g.max_kappa, machine.chord_tolerance_mm, machine.servo_period_s));
  return v;
}

namespace {

// Path acceleration and jerk at speeds up to v (see path_limits).
PathLimits limits_at_cap(const PathGeometry& g, double v, const Machine& machine, double junction_share) noexcept {
  PathLimits l;
  l.max_velocity = v;
  l.max_acceleration = kInf;
  l.max_jerk = kInf;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0 || !(g.tangent[i] > 0.0)) continue;
    const double k = g.curvature[i], t = g.tangent[i];
    double a = (axis.max_acceleration - k * v * v) / t;
    if (k > 0.0 && v > 0.0) a = std::min(a, tolerances::plan_cross_jerk_share * axis.max_jerk / (3.0 * k * v));
    l.max_acceleration = std::min(l.max_acceleration, a);
  }
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0 || !(g.tangent[i] > 0.0)) continue;
    const double j = (1.0 - junction_share) * axis.max_jerk - 3.0 * g.curvature[i] * v * l.max_acceleration -
                     g.curvature_rate[i] * v * v * v;
    l.max_jerk = std::min(l.max_jerk, j / g.tangent[i]);
  }
  return l;
}

}  // namespace

PathLimits path_limits(const PathGeometry& g, double length_mm, double feed_mm_s, const Machine& machine,
                       double junction_jerk_share) noexcept {
  PathLimits best;
  double best_time = kInf;
  const bool curved = !g.curvature.isZero();
  for (const double share : tolerances::plan_centripetal_shares) {
    if (!curved && share != tolerances::plan_centripetal_shares[0]) break;  // one choice on a line
    const double v = speed_cap(g, feed_mm_s, machine, share);
    const PathLimits l = limits_at_cap(g, v, machine, junction_jerk_share);
    // Time estimate: the length at the cap, plus the time to reach the cap and leave it.
    const double time =
        v > 0.0 ? length_mm / v + (std::isfinite(l.max_acceleration) ? v / l.max_acceleration : 0.0) : kInf;
    if (time < best_time || best_time == kInf) {
      best_time = time;
      best = l;
    }
  }
  // A stretch along no axis the machine limits (or of speed 0): the first axis's limits.
  if (!std::isfinite(best.max_acceleration) || !(best.max_acceleration > 0.0))
    best.max_acceleration = machine.axes.front().max_acceleration;
  if (!std::isfinite(best.max_jerk) || !(best.max_jerk > 0.0)) best.max_jerk = machine.axes.front().max_jerk;
  return best;
}

PathLimits path_limits_at(const PathGeometry& g, double cap_mm_s, const Machine& machine,
                          double junction_jerk_share) noexcept {
  PathLimits l = limits_at_cap(g, cap_mm_s, machine, junction_jerk_share);
  if (!std::isfinite(l.max_acceleration) || !(l.max_acceleration > 0.0))
    l.max_acceleration = machine.axes.front().max_acceleration;
  if (!std::isfinite(l.max_jerk) || !(l.max_jerk > 0.0)) l.max_jerk = machine.axes.front().max_jerk;
  return l;
}

PathLimits move_limits(const MoveGeometry& move, const Machine& machine, int samples) {
  const Curve& c = *move.curve;
  const std::vector<double> bp = c.breakpoints();
  PathGeometry g;
  for (std::size_t k = 0; k + 1 < bp.size(); ++k) g.merge(path_geometry(c, bp[k], bp[k + 1], samples));
  return path_limits(g, move.length_mm, move.feed_mm_s, machine, 0.0);
}

double junction_limit(const Derivatives& end_in, const Derivatives& start_out, const Machine& machine,
                      double jerk_share) noexcept {
  const Vec3 dt = unit_tangent(start_out) - unit_tangent(end_in);
  const Vec3 dk = curvature_vector_and_rate(start_out).first - curvature_vector_and_rate(end_in).first;
  double v = kInf;
  const double T = machine.servo_period_s;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0) continue;  // rotary axes do not carry the path
    const double b = std::abs(dt[i]) > tolerances::plan_junction_smooth ? std::abs(dt[i]) / (T * T) : 0.0;
    const double a = std::abs(dk[i]) > tolerances::plan_junction_smooth ? std::abs(dk[i]) / T : 0.0;
    const double c = jerk_share * axis.max_jerk;
    // a v^2 + b v <= c, solved without cancellation
    if (a > 0.0) v = std::min(v, 2.0 * c / (b + std::sqrt(b * b + 4.0 * a * c)));
    else if (b > 0.0) v = std::min(v, c / b);
    // the acceleration spike of a corner, v |dt| / T, within a tenth of the axis's acceleration
    if (b > 0.0) v = std::min(v, 0.1 * axis.max_acceleration * T / std::abs(dt[i]));
  }
  return v;
}

Junction junction(const Derivatives& end_in, const Derivatives& start_out, const Machine& machine) noexcept {
  const Vec3 dt = unit_tangent(start_out) - unit_tangent(end_in);
  const Vec3 dk = curvature_vector_and_rate(start_out).first - curvature_vector_and_rate(end_in).first;
  const double corner = dt.cwiseAbs().maxCoeff();
  if (corner <= tolerances::plan_junction_smooth && dk.cwiseAbs().maxCoeff() <= tolerances::plan_junction_smooth)
    return {kInf, 0.0};
  const double share = corner < tolerances::plan_small_corner ? tolerances::plan_smooth_junction_jerk_share
                                                              : tolerances::plan_corner_jerk_share;
  return {junction_limit(end_in, start_out, machine, share), share};
}

}  // namespace kontur::plan
