#pragma once
// From moves to setpoints: each pushed move (a curve with its feed) gets its path limits, its
// arc-length table and a junction limit with the move before; the look-ahead turns them into
// jerk-limited profiles; next() samples the profiles at the servo period and maps the distance
// along each move to a point by the exact arc length (the planning allocates, next() does not).
#include <kontur/curve.hpp>
#include <kontur/length.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/lookahead.hpp>

#include <deque>
#include <memory>
#include <optional>

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
  long source_line = 0;          ///< line of the move it lies on
};

class MotionPlanner {
public:
  explicit MotionPlanner(const Machine& machine);

  /// Appends a move (planning: computes its table and limits; allocates). A move of zero length
  /// is skipped.
  void push(const MoveInput& move);
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
  struct Planned {
    std::shared_ptr<const Curve> curve;
    std::shared_ptr<const ArcLengthTable> table;
    ScurveProfile profile;
    long source_line = 0;
  };
  struct Pending {
    std::shared_ptr<const Curve> curve;
    std::shared_ptr<const ArcLengthTable> table;
    long source_line = 0;
  };
  void release_ready();

  Machine machine_;
  double period_;
  Lookahead lookahead_;
  std::deque<Pending> pending_;   // moves in the look-ahead window, in order
  std::deque<Planned> planned_;   // moves with final profiles, in order
  std::optional<Derivatives> last_end_;  // end of the last move pushed (for the junction)
  bool finished_ = false;
  // Sampling state
  bool started_ = false;
  bool end_given_ = false;
  double t_ = 0.0;        // time of the last setpoint [s]
  double t_move_ = 0.0;   // time into the current move [s]
  double u_ = 0.0, s_ = 0.0;  // parameter and distance of the last setpoint on the current move
  Vec3 last_position_ = Vec3::Zero();
};

}  // namespace kontur::plan
