#pragma once
// Look-ahead across moves: the speed at every junction, so that braking starts early enough
// (the reason seed 000 computes the length of a spline), and the path limits of a move from its
// geometry and the machine's axis limits.
#include <kontur/geometry/curve.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/scurve.hpp>
#include <kontur/tolerances.hpp>

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
};

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
  [[nodiscard]] ScurveProfile pop();
  /// Moves waiting in the window.
  [[nodiscard]] std::size_t size() const noexcept { return window_.size(); }
  /// Braking evaluations (braking_velocity calls) made so far, for tests of the cost.
  [[nodiscard]] std::size_t braking_evaluations() const noexcept { return evaluations_; }

private:
  void tail_changed() noexcept { tail_dirty_ = true; }
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
  mutable std::size_t evaluations_ = 0;
  double v_start_ = 0.0;
  bool finished_ = false;
};

/// Per-axis bounds of the geometry of a stretch of path, as the limits need them: maxima over
/// samples (plan_samples_per_span per span), raised by tolerances::plan_sample_margin.
struct PathGeometry {
  Vec3 tangent = Vec3::Zero();         ///< max |t_i| of the unit tangent
  Vec3 curvature = Vec3::Zero();       ///< max |K_i| of the curvature vector K = kappa n [1/mm]
  Vec3 curvature_rate = Vec3::Zero();  ///< max |dK_i/ds| along the path [1/mm^2]
  double max_kappa = 0.0;              ///< largest curvature [1/mm] (for the chord error)
  /// The bounds of both stretches.
  void merge(const PathGeometry& other) noexcept;
};

/// Geometry bounds of a curve between parameters u0 < u1 (inside one span, or sampled per span).
[[nodiscard]] PathGeometry path_geometry(const Curve& curve, double u0, double u1,
                                         int samples = tolerances::plan_samples_per_span);

/// Curvature vector K = kappa n = dt/ds [1/mm] and its derivative along the path dK/ds [1/mm^2]
/// from a point's derivatives up to the third (zero where C' = 0).
[[nodiscard]] std::pair<Vec3, Vec3> curvature_vector_and_rate(const Derivatives& d) noexcept;

/// The speed cap [mm/s] of a stretch: the smallest of the feed, the machine's max feed, every
/// axis's velocity along the tangent, the centripetal acceleration K_i v^2 <= share A_i, the
/// curvature change K'_i v^3 <= plan_curvature_rate_jerk_share J_i and the chord-error limit
/// v <= (2/T) sqrt(R^2 - (R - delta)^2); zero if the stretch moves an axis the machine lacks.
[[nodiscard]] double speed_cap(const PathGeometry& g, double feed_mm_s, const Machine& machine,
                               double centripetal_share) noexcept;

/// The path limits of a stretch of length `length_mm`: its speed cap (speed_cap) and the largest
/// path acceleration and jerk that keep every axis within its limits at any speed up to the cap:
/// |t_i| a + K_i v^2 <= A_i, and |t_i| j + 3 K_i v a + K'_i v^3 <= (1 - junction_share) J_i, the
/// cross term taking at most plan_cross_jerk_share. `junction_jerk_share` is the share of the
/// junctions at the stretch's ends (see junction). Of the centripetal shares in
/// tolerances::plan_centripetal_shares, the one with the shortest estimated time is taken.
[[nodiscard]] PathLimits path_limits(const PathGeometry& g, double length_mm, double feed_mm_s,
                                     const Machine& machine, double junction_jerk_share) noexcept;

/// The path limits of a stretch at a given speed cap [mm/s] (as path_limits, without choosing the
/// centripetal share): raising the junction share lowers only the jerk.
[[nodiscard]] PathLimits path_limits_at(const PathGeometry& g, double cap_mm_s, const Machine& machine,
                                        double junction_jerk_share) noexcept;

/// Geometry of a move as the planner sees it: the curve, its length and the largest speed the
/// program asks for.
struct MoveGeometry {
  const Curve* curve = nullptr;  ///< the path
  double length_mm = 0.0;        ///< its length [mm]
  double feed_mm_s = 0.0;        ///< programmed feed (or rapid speed) [mm/s]
};

/// The path limits of a whole move (path_limits over the geometry of all its spans, `samples`
/// per span, with smooth junctions at its ends).
[[nodiscard]] PathLimits move_limits(const MoveGeometry& move, const Machine& machine,
                                     int samples = tolerances::plan_samples_per_span);

/// What a junction of two stretches allows.
struct Junction {
  double velocity = 0.0;     ///< largest speed through it [mm/s] (infinity if smooth)
  double jerk_share = 0.0;   ///< share of each axis's jerk it uses (0 if smooth)
};

/// The junction of two stretches, from the end of the first (`end_in`: point and derivatives up to
/// the second, as the limit from the left) and the start of the second. Setpoints a servo period
/// T apart see a change of direction as a velocity jump, and a change of curvature as an
/// acceleration jump, within one period; each axis's jerk (as a finite difference of the
/// setpoints sees it) stays within `jerk_share` of its limit when
/// v |t1 - t2|_i / T^2 + v^2 |K1 - K2|_i / T <= jerk_share J_i, and the acceleration spike of a
/// corner within 1 - max centripetal share of its limit: v |t1 - t2|_i / T <= 0.1 A_i. Where
/// tangent and curvature agree to plan_junction_smooth there is no limit.
[[nodiscard]] double junction_limit(const Derivatives& end_in, const Derivatives& start_out,
                                    const Machine& machine, double jerk_share = 1.0) noexcept;

/// The junction with the share chosen by its kind: none if smooth, plan_corner_jerk_share for a
/// corner, plan_smooth_junction_jerk_share for a small corner or a curvature jump only.
[[nodiscard]] Junction junction(const Derivatives& end_in, const Derivatives& start_out,
                                const Machine& machine) noexcept;

}  // namespace kontur::plan
