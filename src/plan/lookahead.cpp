#include <kontur/differential.hpp>
#include <kontur/interpolation.hpp>
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

void Lookahead::push(const MoveConstraint& move) { window_.push_back(move); }

bool Lookahead::ready() const {
  if (window_.empty()) return false;
  if (finished_ || window_.size() >= max_window) return true;
  // The oldest move is final when its end speed does not depend on what follows the window: the
  // backward pass gives the same speed at junction 1 whether the window ends at rest or the
  // motion goes on at the last move's cap. (Ending every move at zero acceleration makes braking
  // over many short moves far longer than one braking profile, so no distance rule suffices.)
  auto junction1 = [&](double v_end) {
    double v = v_end;
    for (std::size_t i = window_.size(); i-- > 1;) {
      const double cap = std::min({window_[i - 1].max_end_velocity, window_[i - 1].limits.max_velocity,
                                   window_[i].limits.max_velocity});
      v = std::min(cap, brake_from(v, window_[i]));
    }
    return v;
  };
  const double at_rest = junction1(0.0);
  const double going_on = junction1(window_.back().limits.max_velocity);
  return at_rest >= going_on;
}

ScurveProfile Lookahead::pop() {
  const std::vector<MoveConstraint> w(window_.begin(), window_.end());
  // From where the previous move ended, to rest after the window (final by ready()).
  const std::vector<double> v = plan_junctions(w, v_start_, 0.0);
  ScurveProfile p = plan_scurve(w[0].length_mm, v_start_, v[1], w[0].limits);
  v_start_ = p.end_velocity();
  window_.pop_front();
  return p;
}

PathLimits move_limits(const MoveGeometry& move, const Machine& machine, int samples) {
  PathLimits l;
  l.max_velocity = std::min(move.feed_mm_s, machine.max_feed_mm_s);
  l.max_acceleration = kInf;
  l.max_jerk = kInf;
  const Curve& c = *move.curve;
  samples = std::max(samples, 2);
  for (int k = 0; k <= samples; ++k) {
    const double u = c.u_min() + (c.u_max() - c.u_min()) * k / samples;
    const Derivatives d = c.derivatives(u, 2);
    const Vec3 t = unit_tangent(d);
    if (t.isZero()) continue;
    const double kappa = curvature(d);
    // Principal normal: the part of C'' across the tangent, normalised.
    Vec3 normal = d[2] - d[2].dot(t) * t;
    normal = normal.norm() > 0.0 ? Vec3(normal / normal.norm()) : Vec3::Zero();
    const double share = kappa > 0.0 ? 0.5 : 1.0;  // half of each budget on curves
    for (const AxisLimits& axis : machine.axes) {
      const int i = linear_axis_index(axis.name);
      if (i < 0) continue;  // rotary axes do not carry the path
      const double ti = std::abs(t[i]), ni = std::abs(normal[i]);
      if (ti > 0.0) {
        l.max_velocity = std::min(l.max_velocity, axis.max_velocity / ti);
        l.max_acceleration = std::min(l.max_acceleration, share * axis.max_acceleration / ti);
        l.max_jerk = std::min(l.max_jerk, share * axis.max_jerk / ti);
      }
      if (kappa > 0.0 && ni > 0.0) {
        // centripetal acceleration v^2 kappa n and its jerk ~ v^3 kappa^2 on each axis
        l.max_velocity = std::min(l.max_velocity, std::sqrt(0.5 * axis.max_acceleration / (kappa * ni)));
        l.max_velocity = std::min(l.max_velocity, std::cbrt(0.5 * axis.max_jerk / (kappa * kappa)));
      }
    }
    for (char missing : {'X', 'Y', 'Z'}) {
      // An axis the machine does not have cannot move.
      const int i = linear_axis_index(missing);
      if (machine.axis(missing) == nullptr && std::abs(t[i]) > 1e-12) l.max_velocity = 0.0;
    }
    if (kappa > 0.0)
      l.max_velocity = std::min(l.max_velocity, chord_limited_feed(1.0 / kappa, machine.chord_tolerance_mm,
                                                                   machine.servo_period_s));
  }
  if (!std::isfinite(l.max_acceleration)) l.max_acceleration = machine.axes.front().max_acceleration;
  if (!std::isfinite(l.max_jerk)) l.max_jerk = machine.axes.front().max_jerk;
  return l;
}

namespace {

// Curvature vector kappa n = (C'' - (C''.t) t) / |C'|^2 [1/mm].
Vec3 curvature_vector(const Derivatives& d) noexcept {
  const double v2 = d[1].squaredNorm();
  if (!(v2 > 0.0)) return Vec3::Zero();
  const Vec3 t = d[1] / std::sqrt(v2);
  return (d[2] - d[2].dot(t) * t) / v2;
}

}  // namespace

double junction_limit(const Derivatives& end_in, const Derivatives& start_out, const Machine& machine) noexcept {
  const Vec3 dt = unit_tangent(start_out) - unit_tangent(end_in);
  const Vec3 dk = curvature_vector(start_out) - curvature_vector(end_in);
  double v = kInf;
  const double T = machine.servo_period_s;
  for (const AxisLimits& axis : machine.axes) {
    const int i = linear_axis_index(axis.name);
    if (i < 0) continue;  // rotary axes do not carry the path
    if (std::abs(dt[i]) > 1e-9) v = std::min(v, axis.max_jerk * T * T / std::abs(dt[i]));
    if (std::abs(dk[i]) > 1e-9) v = std::min(v, std::sqrt(axis.max_jerk * T / std::abs(dk[i])));
  }
  return v;
}

}  // namespace kontur::plan
