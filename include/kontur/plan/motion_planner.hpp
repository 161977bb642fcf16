#pragma once
// From moves to the trajectory: each pushed move (a curve with its feed) is cut into pieces whose
// geometry asks for similar speeds (and at every corner or curvature jump inside it), each piece
// gets its path limits and a junction limit with the piece before; the look-ahead turns them into
// jerk-limited profiles, and each piece whose profile is final is appended to the trajectory as a
// time segment (trajectory/trajectory.hpp), which a trajectory::Sampler turns into setpoints.
// Planning allocates; sampling does not.
#include <deque>
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/banded_profile.hpp>
#include <kontur/plan/chain_profile.hpp>
#include <kontur/plan/lookahead.hpp>
#include <kontur/program/move.hpp>
#include <kontur/trajectory/trajectory.hpp>
#include <memory>
#include <optional>
#include <limits>
#include <vector>

namespace kontur::plan {

/// A stretch of one move planned with one profile.
struct MovePiece {
  double u0 = 0.0, u1 = 0.0;        ///< parameter range on the move's curve
  double s0_mm = 0.0, s1_mm = 0.0;  ///< arc-length range on the curve [mm]
  PathGeometry geometry;            ///< bounds of its geometry
  Junction end;                     ///< the junction with the next piece of the same move
  /// It starts (ends) at a stationary point of the curve (C' = 0: a degenerate end): the path
  /// stops there, whatever comes before (after) it.
  bool stationary_start = false, stationary_end = false;
};

/// Cuts a move into pieces: at every breakpoint where tangent or curvature jump (a junction that
/// limits the speed), at every stationary point (C' = 0, a cusp: a stop), and between stretches
/// whose speed caps differ by more than tolerances::plan_piece_cap_ratio (so a short tight bend
/// slows only itself; a span is cut in four where one quarter is that much faster than the whole).
[[nodiscard]] std::vector<MovePiece> split_move(const Curve& curve, const ArcLengthTable& table, double feed_mm_s,
                                                const Machine& machine);

class MotionPlanner {
 public:
  /// Plans on `machine` and appends the final segments to `out` (kept by reference).
  MotionPlanner(const Machine& machine, trajectory::Trajectory& out);

  /// Appends a move (planning: computes its table, pieces and limits; allocates). A move of zero
  /// length is skipped. The extra axes move linearly with the distance and keep their own limits;
  /// a move of the extra axes alone (Move::tool_still) runs over their distance. Frees the segments the sampler has passed (Trajectory::reclaim).
  void push(const program::Move& move);
  /// A dwell (G4): the motion stops at the end of the moves so far and stays there `seconds` [s].
  void dwell(double seconds, long source_line);
  /// No more moves: the last one ends at rest; every segment is appended and the trajectory closed.
  void finish();
  /// Servo period [s].
  [[nodiscard]] double period_s() const noexcept { return period_; }

 private:
  // A piece of a move with its limits, waiting in a chain.
  struct Piece {
    trajectory::Segment segment;  // what the sampler gets (its profile and window set on release)
    PathGeometry geometry;
    double feed_mm_s = 0.0;
    double start_share = 0.0;  // jerk share of the junction at its start
    bool start_smooth = false;  // its start is inside a chain (a smooth junction)
    double start_velocity = 0.0;  // [mm/s] the largest speed through the junction at its start
    double planned_share = 0.0;  // the junction share its limits were chosen for ...
    bool planned_end_smooth = true;  // ... whether its end was taken to be inside a chain ...
    double planned_end_velocity = std::numeric_limits<double>::infinity();  // ... and its speed [mm/s]
    double length_mm = 0.0;
    PathLimits limits;  // final once its end junction is known (settle_last)
    AccelerationBands bands;  // its speed bands (constraints.hpp), set when its chain closes
  };
  // Consecutive pieces joined by smooth junctions (tangent and curvature continuous) with similar
  // speed caps: one entry of the look-ahead, one S-curve over their summed length with the
  // smallest of their limits, so that the speed can change across the junctions between them
  // (acceleration carried through) instead of every piece starting and ending at zero
  // acceleration.
  struct Chain {
    std::vector<Piece> pieces;
    double min_cap_mm_s = 0.0, max_cap_mm_s = 0.0;
    double length_mm = 0.0;    // of its pieces
    double own_time_s = 0.0;   // each piece's length at its own cap, summed
    PathLimits limits;  // what the look-ahead planned it with (set when closed) ...
    AccelerationBands bands;  // ... and its speed bands up to its smallest cap (none on lines)
    bool smooth_end = false;  // the next chain continues it smoothly (it was closed for its caps)
    // Takes a piece's cap, length and time at its cap into the figures above (`first`: they
    // start anew with it).
    void count(const Piece& p, bool first) noexcept;
    // The figures above anew from every piece (after a piece's limits changed or one was removed).
    void recount() noexcept;
  };
  // Raises the cap of each curved piece at a low of the chain's caps (at most its neighbours';
  // cap_before / cap_after [mm/s]: the caps of the pieces beside the chain across smooth
  // junctions, else infinity) and of the pieces around it below that level to their caps at the
  // largest centripetal and curvature-change shares, up to the caps beyond them; not where that
  // would lower the smallest jerk of a chain of several pieces (docs/planner.md, "The lows of a
  // chain").
  void raise_chain_lows(Chain& chain, double cap_before, double cap_after);
  // Adds a piece to the open chain (closing it first if the piece's cap does not fit).
  void add_piece(Piece piece);
  // The chain's profile: the look-ahead plans it as one S-curve at its smallest cap, or under its
  // speed bands where only they reach its end speed; the fastest of that, the profile under the
  // chain's speed bands (plan/banded_profile.hpp) and, where its pieces' caps differ or are curved,
  // one that follows them (plan/chain_profile.hpp).
  [[nodiscard]] trajectory::PathProfile chain_profile(const Chain& chain, const trajectory::PathProfile& planned) const;
  // Appends the chain's pieces as stretches, each with its own cap and limits, and a curved one's
  // limits at lower speeds (its speed bands).
  static void append_stretches(const Chain& chain, std::vector<CapStretch>& out);
  // The profile that follows each stretch's cap and limits from v0 to v1 [mm/s] (none where it
  // cannot be planned), stepped at a share of the ramp time of `least`, the smallest limits.
  [[nodiscard]] std::optional<trajectory::PathProfile> following_profile(std::span<const CapStretch> stretches,
                                                                         double v0, double v1, const PathLimits& least,
                                                                         double time_bound_s) const;
  // The chain's speed bands up to its smallest cap (none where its pieces are lines).
  [[nodiscard]] AccelerationBands chain_bands(const Chain& chain) const;
  // The open chain's last piece gets its end junction's share; its limits become final.
  void settle_last(double end_share, bool end_smooth, double end_velocity);
  // The limits of a piece whose ends have these junction shares and are or are not inside a chain.
  [[nodiscard]] PathLimits piece_limits(const Piece& piece, double share, bool end_smooth, double end_velocity) const;
  // Closes the open chain (its end speed at most `end_velocity`) and hands it to the look-ahead;
  // `next_cap_mm_s` [mm/s]: the cap of the piece that opens the next chain across a smooth junction
  // (infinity where not known or not smooth).
  void close_chain(double end_velocity, double next_cap_mm_s = std::numeric_limits<double>::infinity());
  // Hands the chains whose profiles are final to the trajectory, holding those that join the next
  // smoothly until that one's is final too.
  void release_ready();
  // Releases the held chains: each through its own profile, or runs of them through one profile
  // where that is faster.
  void release_held();
  // Held chains first .. last - 1: through one profile, or each through its own.
  struct Run {
    std::size_t first = 0, last = 0;
    std::optional<trajectory::PathProfile> profile;  // none: each through its own
  };
  // The fastest way to run held chains first .. last - 1 (all through one profile, each through
  // its own, or where neither wins, each half the fastest way), appended to `out`; its time [s].
  double fastest_runs(std::size_t first, std::size_t last, const std::vector<trajectory::PathProfile>& own,
                      std::vector<Run>& out) const;
  // Appends the pieces of `chain` to the trajectory, running through `profile` from distance
  // offset [mm] and time t0 [s].
  void release_chain(Chain& chain, const trajectory::PathProfile& profile, double& offset, double& t0, bool last);

  Machine machine_;
  double period_;
  trajectory::Trajectory* out_;
  Lookahead lookahead_;
  std::deque<Chain> pending_;            // closed chains in the look-ahead window, in order
  struct Planned {
    Chain chain;
    trajectory::PathProfile planned;  // the look-ahead's
  };
  std::vector<Planned> held_;            // chains out of the look-ahead, each joining the next smoothly
  std::size_t held_pieces_ = 0;          // their pieces, those of one move counted once
  Chain open_;                           // the chain being built (its last piece's end not yet known)
  std::optional<Derivatives> last_end_;  // end of the last move pushed (for the junction)
  // [mm/s] the cap of the last piece of the chain closed last where it ended smoothly, else infinity
  double last_chain_end_cap_mm_s_ = std::numeric_limits<double>::infinity();
  std::vector<double> raise_to_, raise_tops_;  // raise_chain_lows' buffers (kept between chains)
  ExtraAxes last_rate_{};                // its extra axes' rates dq/ds (signed)
  bool last_tool_still_ = false;         // only its extra axes moved
  bool last_stationary_end_ = false;     // its curve ends at a stationary point (C' = 0)
  bool last_exact_stop_ = true;          // the last move pushed ends at rest
  // The share of the last junction that is not smooth, and the time [s] after it (a lower bound:
  // the pieces passed at their caps) within which the pieces still plan with it
  // (tolerances::plan_junction_share_reach_periods).
  double reach_share_ = 0.0;
  double reach_left_s_ = 0.0;
  /// Starts the reach of a junction that is not smooth.
  void reach_from(const Junction& j) noexcept;
  double initial_hold_s_ = 0.0;          // dwell before the next move, with nothing pending [s]
  long initial_hold_line_ = 0;
  program::MoveId last_move_ = program::no_move;  // the last move pushed with a length
  bool finished_ = false;
};

}  // namespace kontur::plan
