#pragma once
// The time-optimal reference of issue 5: the fastest acceleration-limited path speed profile
// s_dot(s) along a whole sequence of moves, computed offline by reachability analysis on a grid
// of arc length (the TOPP-RA formulation: in x = s_dot^2 and u = s_ddot every axis constraint is
// linear, a backward pass gives the largest controllable x at every grid point, a greedy forward
// pass the profile). Jerk is ignored: it is a lower bound on the time of any planner that keeps
// the same velocity, acceleration, feed and chord limits (docs/planner.md, "Time-optimal
// reference").
#include <kontur/geometry/curve.hpp>
#include <kontur/machine.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace kontur::plan {

/// One move of the path as the reference sees it.
struct TimeOptimalMove {
  const Curve* curve = nullptr;  ///< the path of the move (must outlive the call)
  double feed_mm_s = 0.0;        ///< programmed path speed [mm/s], > 0
  bool exact_stop = false;       ///< the move ends at rest (G61, the program's last move)
};

/// What happens at a tangent discontinuity (a corner between moves or at a C0 knot inside one).
enum class CornerRule {
  /// Continuous time: a velocity jump needs infinite acceleration, so a corner is a stop.
  stop,
  /// Sampled time: the velocity jump across the corner happens within one servo period T, which
  /// the finite differences of the setpoints see as an acceleration v |dt_i| / T; the corner
  /// speed is the largest with v |dt_i| <= A_i T on every axis (dt = jump of the unit tangent).
  /// This is the acceleration-limited counterpart of the online planner's junction rule.
  servo_period,
};

/// Discretisation of the reference.
struct TimeOptimalOptions {
  double max_step_mm = 0.05;         ///< largest grid step along the path [mm]
  int min_intervals_per_move = 16;   ///< fewest grid intervals on a move (short moves, arcs)
  /// Largest turn of the unit tangent over one grid interval [rad] (|t_a - t_b|): intervals that
  /// turn more are bisected (tight arcs, near-cusps of splines), down to
  /// tolerances::time_optimal_min_step_mm.
  double max_turn_rad = 0.02;
  CornerRule corners = CornerRule::stop;  ///< speed at tangent discontinuities
  /// Largest uniform grid (the step grows to stay within it; about 170 bytes per point). The
  /// refinement at sharp turns comes on top.
  std::size_t max_points = 2'000'000;
};

/// The time-optimal profile on its grid. Grid point k is at arc length s_mm[k] from the path's
/// start; the segment [k, k+1] lies on move move_index[k] and its acceleration was checked at k
/// (collocation), with the constant path acceleration (v_{k+1}^2 - v_k^2) / (2 (s_{k+1} - s_k)).
struct TimeOptimalProfile {
  std::vector<double> s_mm;          ///< grid: arc length from the start [mm]
  std::vector<double> v_mm_s;        ///< optimal path speed s_dot at each grid point [mm/s]
  std::vector<double> mvc_mm_s;      ///< maximum velocity curve (largest admissible speed) [mm/s]
  std::vector<std::size_t> move_index;  ///< move of the segment that starts at point k (last point: last move)
  std::vector<double> move_s_mm;     ///< arc length of point k on that move [mm]
  /// Time of the whole path [s]: per segment 2 ds / (v_k + v_{k+1}) where the acceleration bound
  /// is active over the whole segment; where the profile reaches a cap inside a segment, the
  /// exact time of accelerating (braking) at the bound and cruising at the higher end speed.
  double total_time_s = 0.0;
  /// Time of each input move [s] (indexed as `moves`; 0 for a move of zero length): the times of
  /// the segments that lie on it, as total_time_s counts them, so that they add up to it (to
  /// rounding). Where the planner's time on a move is far above this, that move loses the time.
  std::vector<double> move_time_s;
  double length_mm = 0.0;            ///< length of the whole path [mm]
  std::size_t corners = 0;           ///< tangent discontinuities found (stops or servo-period corners)
};

/// The time-optimal profile from rest to rest along `moves` on `machine`: per axis
/// |s_dot t_i| <= V_i and |t_i s_ddot + k_i s_dot^2| <= A_i (t the unit tangent, k = kappa n the
/// curvature vector, derivatives by arc length), s_dot <= min(feed, max feed), the chord limit
/// s_dot <= (2/T) sqrt(R^2 - (R - delta)^2), rest at exact stops and corners (CornerRule).
/// Moves of zero length are skipped. Rotary axes do not carry the path. Throws InputError for a
/// move without a curve, a feed <= 0 or a path along an axis the machine does not have (its speed
/// cap is zero: the rule of plan/constraints.hpp, which the online planner follows too).
[[nodiscard]] TimeOptimalProfile time_optimal_profile(std::span<const TimeOptimalMove> moves, const Machine& machine,
                                                      const TimeOptimalOptions& options = {});

}  // namespace kontur::plan
