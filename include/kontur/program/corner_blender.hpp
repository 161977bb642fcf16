#pragma once
// Corner blending within the G64 path tolerance: a streaming stage over the program's moves. At a
// corner between two lines (G0 / G1) that is not tangent, where the first move does not stop
// exactly (G61 / G61.1) and the tolerance is positive, both lines are trimmed by a distance d and
// a CornerBlendCurve (geometry/corner_blend_curve.hpp) joins them, tangent to both lines and with
// zero curvature at both ends. d is the largest distance for which the blend stays within the
// tolerance of the two programmed lines, and at most 45 % of each line's length (a line between
// two blended corners keeps a straight middle).
// Where an arc (G2 / G3) meets a line or another arc at a corner, or tangent but with a jump of
// curvature (a line running into an arc: the acceleration would jump by v^2 / R), both moves are
// trimmed by the arc length d and a TransitionCurve (geometry/transition_curve.hpp) joins them,
// tangent and curvature-continuous with both; d is found by shrinking it from 45 % of each move
// until the blend is within the tolerance of the programmed pieces it replaces.
#include <functional>
#include <kontur/geometry/corner_blend_curve.hpp>
#include <kontur/machine.hpp>
#include <kontur/program/move.hpp>
#include <optional>
#include <vector>

namespace kontur::program {

/// The speed [mm/s] a blend curve can be run at on the machine with a programmed feed [mm/s]:
/// what planning will allow (the pipeline gives plan::speed_cap; the program stage does not plan).
using BlendSpeed = std::function<double(const Curve& blend, double feed_mm_s)>;
/// How planning passes a junction left as it is: its largest speed [mm/s] (0 for a stop) and the
/// share of each axis's jerk it takes from the moves on both sides.
struct JunctionPass {
  double velocity_mm_s = 0.0;
  double jerk_share = 0.0;
};
/// The junction pass from the incoming move's end and the outgoing move's start (the pipeline
/// gives plan::junction's).
using JunctionSpeed = std::function<JunctionPass(const Derivatives& end_in, const Derivatives& start_out)>;

/// The streaming blender: holds back one line or arc move until the next move is known.
class CornerBlender {
 public:
  /// `enabled` false: every move is handed on as given (`kontur run --no-blend`). With a machine
  /// (kept by pointer) and its `speed`, a junction is blended only where that is estimated to be
  /// faster than leaving it (docs/planner.md, "Corner blending"): over half of each move, the blend
  /// at its speed and speeding up from it, against speeding up from the junction's speed (a stop at
  /// a corner between lines; `junction`'s where an arc is involved, with the jerk share it takes).
  explicit CornerBlender(bool enabled = true, const Machine* machine = nullptr, BlendSpeed speed = {},
                         JunctionSpeed junction = {})
      : enabled_(enabled), machine_(machine), speed_(std::move(speed)), junction_(std::move(junction)) {}
  /// The next move of the program (its corner_tolerance_mm is the tolerance of the corner at its
  /// end; 0 = no blend). The moves that are ready are appended to `out`, in order: trimmed lines
  /// (their length recomputed), trimmed arcs (their pieces, CurvePiece) and blends (type "blend",
  /// with the programmed corner, the source line and feed of the outgoing move).
  void push(const Move& move, std::vector<Move>& out);
  /// A dwell or the end of the program: the move held back is handed on.
  void flush(std::vector<Move>& out);

 private:
  struct Held {
    Move move;                                    // as programmed
    Vec3 start = Vec3::Zero();                    // where it starts now (trimmed by the blend before) [mm]
    Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the programmed move's ends [mm]
    double u_start = 0.0;                         // the parameter of `start` on the programmed curve
    bool line = true;                             // a line (else an arc)
    // The programmed lines running straight on into it, untrimmed and joined smoothly [mm]: the
    // straight stretch a corner at its end is approached along (the blender's estimate times it).
    double straight_before_mm = 0.0;
  };
  // The held move from where it starts now up to the point `end` (a line: from `start`) or up to
  // the parameter `u_end` of its programmed curve (an arc: its piece from u_start); as programmed
  // where it is not trimmed.
  [[nodiscard]] Move held_until(const Vec3& end, double u_end) const;
  // Blends the junction of the held move with `move` where one of them is an arc; false where it
  // is not blended (nothing is handed on then).
  bool blend_with_arc(const Move& move, bool move_is_line, std::vector<Move>& out);
  bool enabled_;
  const Machine* machine_;
  BlendSpeed speed_;
  JunctionSpeed junction_;
  std::optional<Held> held_;
};

}  // namespace kontur::program
