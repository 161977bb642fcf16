#pragma once
// From moves to setpoints: each pushed move (a curve with its feed) is cut into pieces whose
// geometry asks for similar speeds (and at every corner or curvature jump inside it), each piece
// gets its path limits and a junction limit with the piece before; the look-ahead turns them into
// jerk-limited profiles; next() samples the profiles at the servo period and maps the distance
// along each piece to a point by the exact arc length (the planning allocates, next() does not).
#include <kontur/geometry/curve.hpp>
#include <kontur/geometry/length.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/lookahead.hpp>

#include <deque>
#include <memory>
#include <optional>
#include <vector>

namespace kontur::plan {

/// A move to run.
struct MoveInput {
  std::shared_ptr<const Curve> curve;  ///< the path of the move (shared: the planner keeps it while needed)
  double feed_mm_s = 0.0;              ///< programmed path speed [mm/s] (rapid: the machine's rapid feed)
  bool exact_stop = false;             ///< stop at the end of this move (G61, or the program's last move)
  long source_line = 0;                ///< line of the program the move comes from
};

/// One setpoint of the servo loop.
struct Setpoint {
  double t_s = 0.0;              ///< time since the start [s]
  Vec3 position = Vec3::Zero();  ///< tool position [mm]
  double v_mm_s = 0.0;           ///< planned path speed [mm/s]
  long source_line = 0;          ///< line of the move it lies on (of the dwell, while dwelling)
};

/// A stretch of one move planned with one profile.
struct MovePiece {
  double u0 = 0.0, u1 = 0.0;          ///< parameter range on the move's curve
  double s0_mm = 0.0, s1_mm = 0.0;    ///< arc-length range on the curve [mm]
  PathGeometry geometry;              ///< bounds of its geometry
  Junction end;                       ///< the junction with the next piece of the same move
};

/// Cuts a move into pieces: at every breakpoint where tangent or curvature jump (a junction that
/// limits the speed), and between spans whose speed caps differ by more than
/// tolerances::plan_piece_cap_ratio (so a short tight bend slows only itself).
[[nodiscard]] std::vector<MovePiece> split_move(const Curve& curve, const ArcLengthTable& table, double feed_mm_s,
                                                const Machine& machine);

class MotionPlanner {
public:
  explicit MotionPlanner(const Machine& machine);

  /// Appends a move (planning: computes its table, pieces and limits; allocates). A move of zero
  /// length is skipped.
  void push(const MoveInput& move);
  /// A dwell (G4): the motion stops at the end of the moves so far and stays there `seconds` [s].
  void dwell(double seconds, long source_line);
  /// No more moves: the last one ends at rest.
  void finish();
  /// The next setpoint: false when the planner needs more moves (or is done, see done()).
  /// The first setpoint is the start point at t = 0. noexcept, allocation-free.
  bool next(Setpoint& out) noexcept;
  /// True once the last setpoint (the end of the last move, at rest) was given.
  [[nodiscard]] bool done() const noexcept { return finished_ && end_given_; }
  /// Servo period [s].
  [[nodiscard]] double period_s() const noexcept { return period_; }

private:
  struct Piece {
    std::shared_ptr<const Curve> curve;
    std::shared_ptr<const ArcLengthTable> table;
    double u0 = 0.0, u1 = 0.0, s0 = 0.0, s1 = 0.0;
    long source_line = 0;
    double hold_before_s = 0.0;  // dwell before the motion (a dwell ahead of the first move) [s]
    double hold_after_s = 0.0;   // dwell after it [s]
    long hold_line = 0;          // line of that dwell
    // what the limits were computed from (the share may rise when the next junction is known)
    PathGeometry geometry;
    double feed_mm_s = 0.0;
    double start_share = 0.0;
    double cap_mm_s = 0.0;       // its speed cap [mm/s]
    ScurveProfile profile;       // final once released by the look-ahead
    [[nodiscard]] double duration() const noexcept { return hold_before_s + profile.duration() + hold_after_s; }
  };
  void release_ready();
  // The end junction of the last move pushed is known (share of the jerk it takes): raise its jerk.
  void settle_last(double end_share);

  Machine machine_;
  double period_;
  Lookahead lookahead_;
  std::deque<Piece> pending_;   // pieces in the look-ahead window, in order
  std::deque<Piece> planned_;   // pieces with final profiles, in order
  std::optional<Derivatives> last_end_;  // end of the last move pushed (for the junction)
  bool last_exact_stop_ = true;          // the last move pushed ends at rest
  double initial_hold_s_ = 0.0;          // dwell before the first move [s]
  long initial_hold_line_ = 0;
  bool finished_ = false;
  // Sampling state
  bool started_ = false;
  bool end_given_ = false;
  double t_ = 0.0;        // time of the last setpoint [s]
  double t_move_ = 0.0;   // time into the current piece [s]
  double u_ = 0.0, s_ = 0.0;  // parameter and distance on the curve of the last setpoint
  Vec3 last_position_ = Vec3::Zero();
};

}  // namespace kontur::plan
