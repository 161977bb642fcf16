#include <kontur/plan/lookahead.hpp>
#include <kontur/tolerances.hpp>

#include "bisection.hpp"

#include <algorithm>

namespace kontur::plan {
namespace {

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
  // Backward: each junction must allow braking to the next within the move between (or to any end
  // speed below it: braking_velocity is monotone in v_after, so rest after a window is the most
  // conservative assumption).
  for (std::size_t i = n; i-- > 1;) v[i] = std::min(v[i], braking_velocity(v[i + 1], moves[i]));
  // Forward: and reaching it from the one before.
  for (std::size_t i = 0; i < n; ++i) v[i + 1] = std::min(v[i + 1], reachable_velocity(v[i], moves[i]));
  return v;
}

}  // namespace

double reachable_velocity(double v_from, const MoveConstraint& m) noexcept {
  const double v = reachable_velocity(v_from, m.length_mm, m.limits);
  if (m.bands.n == 0 || !(v < m.limits.max_velocity)) return v;
  return std::max(v, std::min(m.limits.max_velocity, banded_reachable_velocity(v_from, m.length_mm, m.bands)));
}

double braking_velocity(double v_after, const MoveConstraint& m) noexcept {
  const double v = braking_velocity(v_after, m.length_mm, m.limits);
  if (m.bands.n == 0 || !(v < m.limits.max_velocity)) return v;
  return std::min(m.limits.max_velocity, banded_braking_velocity(v_after, m.length_mm, m.bands, v));
}

trajectory::PathProfile move_profile(const MoveConstraint& m, double v0, double v1) {
  const PathLimits& l = m.limits;
  // (the S-curve's change fits: speeding up within its reach, braking within the length)
  const auto scurve_fits = [&](double w) {
    return w >= v0 ? !(w > reachable_velocity(v0, m.length_mm, l))
                   : detail::fits(velocity_change_distance(w, v0, l.max_acceleration, l.max_jerk), m.length_mm);
  };
  if (scurve_fits(v1) || m.bands.n == 0) return trajectory::PathProfile(plan_scurve(m.length_mm, v0, v1, l));
  if (auto p = plan_banded_profile(m.length_mm, v0, v1, m.bands)) return std::move(*p);
  // Braking to v1 fits neither: the look-ahead's bound on the longest braking under the bands
  // (banded_braking_velocity) missed the end speed that takes longest by a little. Braking to a
  // lower speed is safe for what follows (from a lower speed every later junction is in reach of
  // the next move's forward pass); the first of a descending ladder that fits is taken.
  for (int k = 1; k <= tolerances::plan_banded_braking_fallback_steps; ++k) {
    const double w = v1 * (1.0 - static_cast<double>(k) / tolerances::plan_banded_braking_fallback_steps);
    if (scurve_fits(w)) return trajectory::PathProfile(plan_scurve(m.length_mm, v0, w, l));
    if (auto p = plan_banded_profile(m.length_mm, v0, w, m.bands)) return std::move(*p);
  }
  return trajectory::PathProfile(plan_scurve(m.length_mm, v0, v1, l));
}

std::vector<double> junction_velocities(std::span<const MoveConstraint> moves) { return plan_junctions(moves, 0.0, 0.0); }

double Lookahead::junction_cap(std::size_t i) const noexcept {
  return std::min({window_[i - 1].max_end_velocity, window_[i - 1].limits.max_velocity, window_[i].limits.max_velocity});
}

double Lookahead::brake_at(std::size_t i, double v_after) const {
  ++evaluations_;
  return braking_velocity(v_after, window_[i]);
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
  not_ready_seen_ = false;
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
  if (skip_checks_ > 0 || not_ready_seen_) return false;
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
  not_ready_seen_ = final_.empty();
  return !final_.empty();
}

trajectory::PathProfile Lookahead::pop() {
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
  v1 = std::min(v1, reachable_velocity(v_start_, m));
  trajectory::PathProfile p = move_profile(m, v_start_, v1);
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

}  // namespace kontur::plan
