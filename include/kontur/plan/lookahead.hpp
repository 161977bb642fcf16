#pragma once
// Look-ahead across moves: the speed at every junction, so that braking starts early enough
// (the reason seed 000 computes the length of a spline). The path limits of a move from its
// geometry and the machine's axis limits are in constraints.hpp (included here for callers).
#include <kontur/plan/banded_profile.hpp>
#include <kontur/plan/constraints.hpp>
#include <kontur/plan/scurve.hpp>

#include <algorithm>
#include <deque>
#include <span>
#include <utility>
#include <vector>

namespace kontur::plan {

/// What the look-ahead needs of one move.
struct MoveConstraint {
  double length_mm = 0.0;         ///< path length [mm]
  PathLimits limits;              ///< speed cap, path acceleration and jerk of the move
  double max_end_velocity = 0.0;  ///< largest speed at the junction with the next move [mm/s]
  /// On a curve: more path acceleration at lower speeds (the last top limits.max_velocity; n = 0:
  /// none). The move speeds up and brakes by the S-curve at `limits` or under these bands,
  /// whichever reaches further.
  AccelerationBands bands{};
};

/// The largest speed [mm/s] a move can reach from v_from (and, by symmetry, brake to v_from from)
/// over its length: at its limits, or under its bands where they reach further.
[[nodiscard]] double reachable_velocity(double v_from, const MoveConstraint& m) noexcept;
/// The largest speed [mm/s] at the move's start from which it can brake to v_after, or to any end
/// speed between (braking_velocity, banded_braking_velocity).
[[nodiscard]] double braking_velocity(double v_after, const MoveConstraint& m) noexcept;
/// The move's profile from v0 to v1 [mm/s] as the look-ahead planned them: the S-curve at its
/// limits where that change fits, else under its bands.
[[nodiscard]] trajectory::PathProfile move_profile(const MoveConstraint& m, double v0, double v1);

/// Junction speeds v_0 .. v_N of a whole sequence that starts and ends at rest: the largest that
/// respect every cap and junction limit and that each move can accelerate or brake between
/// (a backward pass for braking, a forward pass for acceleration).
[[nodiscard]] std::vector<double> junction_velocities(std::span<const MoveConstraint> moves);

/// The same as a bounded window for streaming: push moves in order; the oldest move's profile can
/// be taken once later moves can no longer change it (the window's moves suffice to brake to
/// whatever follows), after finish(), or when the window holds max_window moves (then the plan
/// assumes rest after the window: safe, possibly slower).
///
/// Cost: the backward pass "going on at the last move's cap" is cached per junction and updated
/// from the end of the window backwards only until a value is unchanged (usually one or two
/// evaluations per push). The readiness test runs the pass "rest after the window" from the end
/// until it meets the cached one (then both agree on every earlier junction: those are final and
/// kept); when that takes more than check_defer_min evaluations, the next
/// check_defer_share-th as many pushes skip the test (the moves are released a little later, at
/// most about w / check_defer_share moves, with the same speeds), so a window of w tiny moves
/// costs O(check_defer_share) evaluations per push amortized, not O(w). pop() takes a final junction speed and steps forward from the previous move's end.
class Lookahead {
public:
  /// Largest number of moves held.
  static constexpr std::size_t max_window = 100000;
  /// Readiness tests cheaper than this many braking evaluations are never skipped.
  static constexpr std::size_t check_defer_min = 64;
  /// After a test of c evaluations, the next c / check_defer_share pushes skip it.
  static constexpr std::size_t check_defer_share = 4;

  /// Appends a move.
  void push(const MoveConstraint& move);
  /// Lowers the end speed limit of the last move pushed (the junction with the move that
  /// follows, known only when that one arrives).
  void limit_last_end_velocity(double v) noexcept {
    if (window_.empty()) return;
    window_.back().max_end_velocity = std::min(window_.back().max_end_velocity, v);
    tail_changed();
  }
  /// The last move pushed (its limits may still be lowered until the next one arrives; any call
  /// counts as a change of the tail of the window).
  [[nodiscard]] MoveConstraint& back() noexcept {
    tail_changed();
    return window_.back();
  }
  /// No more moves: the last one ends at rest.
  void finish() noexcept { finished_ = true; }
  /// True when the oldest move's profile is final.
  [[nodiscard]] bool ready() const;
  /// The oldest move's profile (requires ready()); removes it from the window.
  [[nodiscard]] trajectory::PathProfile pop();
  /// Moves waiting in the window.
  [[nodiscard]] std::size_t size() const noexcept { return window_.size(); }
  /// Braking evaluations (braking_velocity calls) made so far, for tests of the cost.
  [[nodiscard]] std::size_t braking_evaluations() const noexcept { return evaluations_; }

private:
  void tail_changed() noexcept {
    tail_dirty_ = true;
    not_ready_seen_ = false;
  }
  // Cap of junction i (1 <= i < size()): its own limit and both neighbours' caps [mm/s].
  [[nodiscard]] double junction_cap(std::size_t i) const noexcept;
  // The speed at junction i from which move i can brake to v_after [mm/s] (counted).
  [[nodiscard]] double brake_at(std::size_t i, double v_after) const;
  // Re-runs the cached "going on" pass from the end until a value at or below junction
  // `stop_from` is unchanged (above it, junctions have changed inputs of their own).
  void update_going_on(std::size_t stop_from) const;
  // True (once) if the last move differs from what the cached passes saw.
  [[nodiscard]] bool tail_changed_since_seen() const noexcept;
  // Brings the cached passes up to date with a changed last move.
  void refresh_tail() const;
  // The full "rest after the window" pass into rest_ (for finish() and a full window).
  void update_rest() const;

  std::deque<MoveConstraint> window_;
  // Per junction j = 0 .. size() (j between moves j-1 and j; entry 0 unused) [mm/s]:
  mutable std::deque<double> going_on_;  // backward pass from the last move's cap after the window
  mutable std::deque<double> rest_;      // backward pass from rest after the window (if rest_valid_)
  mutable std::deque<double> final_;     // known final speeds of junctions 1, 2, ... [mm/s]
  mutable bool rest_valid_ = false;
  mutable bool tail_dirty_ = false;      // back() or limit_last_end_velocity since tail_seen_
  mutable MoveConstraint tail_seen_;     // the last move as the cached passes saw it
  mutable std::size_t skip_checks_ = 0;  // pushes before the next readiness test
  // The last readiness test found nothing final and the window has not changed since: the next
  // gives the same answer (the motion planner asks after every move, pushes only closed chains).
  mutable bool not_ready_seen_ = false;
  mutable std::size_t evaluations_ = 0;
  double v_start_ = 0.0;
  bool finished_ = false;
};

}  // namespace kontur::plan
