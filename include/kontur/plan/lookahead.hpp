#pragma once
// Look-ahead across moves: the speed at every junction, so that braking starts early enough
// (the reason seed 000 computes the length of a spline), and the path limits of a move from its
// geometry and the machine's axis limits.
#include <kontur/curve.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/scurve.hpp>

#include <algorithm>
#include <deque>
#include <span>
#include <vector>

namespace kontur::plan {

/// What the look-ahead needs of one move.
struct MoveConstraint {
  double length_mm = 0.0;         ///< path length [mm]
  PathLimits limits;              ///< speed cap, path acceleration and jerk of the move
  double max_end_velocity = 0.0;  ///< largest speed at the junction with the next move [mm/s]
};

/// Junction speeds v_0 .. v_N of a whole sequence that starts and ends at rest: the largest that
/// respect every cap and junction limit and that each move can accelerate or brake between
/// (a backward pass for braking, a forward pass for acceleration).
[[nodiscard]] std::vector<double> junction_velocities(std::span<const MoveConstraint> moves);

/// The same as a bounded window for streaming: push moves in order; the oldest move's profile can
/// be taken once later moves can no longer change it (the window's moves suffice to brake to
/// whatever follows), after finish(), or when the window holds max_window moves (then the plan
/// assumes rest after the window: safe, possibly slower).
class Lookahead {
public:
  /// Largest number of moves held.
  static constexpr std::size_t max_window = 100000;

  /// Appends a move.
  void push(const MoveConstraint& move);
  /// Lowers the end speed limit of the last move pushed (the junction with the move that
  /// follows, known only when that one arrives).
  void limit_last_end_velocity(double v) noexcept {
    if (!window_.empty()) window_.back().max_end_velocity = std::min(window_.back().max_end_velocity, v);
  }
  /// No more moves: the last one ends at rest.
  void finish() noexcept { finished_ = true; }
  /// True when the oldest move's profile is final.
  [[nodiscard]] bool ready() const;
  /// The oldest move's profile (requires ready()); removes it from the window.
  [[nodiscard]] ScurveProfile pop();
  /// Moves waiting in the window.
  [[nodiscard]] std::size_t size() const noexcept { return window_.size(); }

private:
  std::deque<MoveConstraint> window_;
  double v_start_ = 0.0;
  bool finished_ = false;
};

/// Geometry of a move as the planner sees it: the curve, its length and the largest speed the
/// program asks for.
struct MoveGeometry {
  const Curve* curve = nullptr;  ///< the path
  double length_mm = 0.0;        ///< its length [mm]
  double feed_mm_s = 0.0;        ///< programmed feed (or rapid speed) [mm/s]
};

/// The path limits of a move on a machine: the speed cap is the smallest of the feed, the
/// machine's max feed, every axis's velocity along the tangent, the chord-error limit
/// (v <= (2/T) sqrt(R^2 - (R - delta)^2)), the centripetal acceleration and jerk (half of each
/// axis's budget on curves); path acceleration and jerk are each axis's limit over the tangent's
/// share (half on curves). Sampled at `samples` points along the curve.
[[nodiscard]] PathLimits move_limits(const MoveGeometry& move, const Machine& machine, int samples = 64);

/// The largest speed [mm/s] through the junction of two moves, from the end of the first
/// (`end_in`: point and derivatives, as the limit from the left) and the start of the second.
/// Setpoints a servo period T apart see a change of direction as a velocity jump, and a change of
/// curvature as an acceleration jump, within one period; each axis's jerk (as a finite difference
/// of the setpoints sees it) stays within its limit when v |t1 - t2|_axis <= J_axis T^2 and
/// v^2 |k1 - k2|_axis <= J_axis T, with k = kappa n the curvature vector. A real corner is then a
/// near stop; where tangent and curvature agree to 1e-9 there is no limit (infinity).
[[nodiscard]] double junction_limit(const Derivatives& end_in, const Derivatives& start_out,
                                    const Machine& machine) noexcept;

}  // namespace kontur::plan
