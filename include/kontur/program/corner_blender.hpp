#pragma once
// Corner blending within the G64 path tolerance: a streaming stage over the program's moves. At a
// corner between two lines (G0 / G1) that is not tangent, where the first move does not stop
// exactly (G61 / G61.1) and the tolerance is positive, both lines are trimmed by a distance d and
// a CornerBlendCurve (geometry/corner_blend_curve.hpp) joins them, tangent to both lines and with
// zero curvature at both ends. d is the largest distance for which the blend stays within the
// tolerance of the two programmed lines, and at most 45 % of each line's length (a line between
// two blended corners keeps a straight middle).
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

/// The streaming blender: holds back one line move until the next move is known.
class CornerBlender {
 public:
  /// `enabled` false: every move is handed on as given (`kontur run --no-blend`). With a machine
  /// (kept by pointer) and its `speed`, a corner is blended only where that is estimated to be
  /// faster: the blend of length ~2d at that speed against stopping at the corner and starting
  /// again within d on each side at the smallest axis jerk (tiny blends on very short lines bend
  /// so sharply that the jerk of the curvature change makes them slower than the stop).
  explicit CornerBlender(bool enabled = true, const Machine* machine = nullptr, BlendSpeed speed = {})
      : enabled_(enabled), machine_(machine), speed_(std::move(speed)) {}
  /// The next move of the program (its corner_tolerance_mm is the tolerance of the corner at its
  /// end; 0 = no blend). The moves that are ready are appended to `out`, in order: trimmed lines
  /// (their length recomputed) and blends (type "blend", with the programmed corner, the source
  /// line and feed of the outgoing move).
  void push(const Move& move, std::vector<Move>& out);
  /// A dwell or the end of the program: the move held back is handed on.
  void flush(std::vector<Move>& out);

 private:
  struct Held {
    Move move;
    Vec3 start = Vec3::Zero();                    // where it starts now (trimmed by the blend before) [mm]
    Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // the programmed line [mm]
  };
  bool enabled_;
  const Machine* machine_;
  BlendSpeed speed_;
  std::optional<Held> held_;
};

}  // namespace kontur::program
