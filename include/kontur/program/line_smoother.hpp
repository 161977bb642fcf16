#pragma once
// Smoothing of dense G01 within the G64 tolerance: a streaming stage over the program's moves,
// before the corner blender. A run of feed lines (G1) joined without an exact stop, with the same
// positive tolerance (G64 P, else the machine's path tolerance; G64 Q when it is larger), turning
// by at most 30 degrees at each vertex and whose inner lines are at most 50 tolerances long, is
// replaced by one curvature-continuous curve (geometry/polyline_fit.hpp) within the tolerance of
// the programmed lines: its first and last line stay lines (the corners around the run are the
// blender's), each line between them becomes its piece of the curve (a move with the line's
// source line, feed and tag, and the programmed lines it replaces, which the checker measures
// every setpoint against). Runs are cut after 2,000 lines (a bounded window); a run the fit
// cannot keep within the tolerance stays as programmed.
#include <kontur/program/move.hpp>
#include <vector>

namespace kontur::program {

class LineSmoother {
 public:
  /// `enabled` false: every move is handed on as given (`kontur run --no-smooth`).
  explicit LineSmoother(bool enabled = true) : enabled_(enabled) {}
  /// The next move of the program; the moves that are ready are appended to `out`, in order.
  void push(const Move& move, std::vector<Move>& out);
  /// A dwell or the end of the program: the run held back is handed on.
  void flush(std::vector<Move>& out);

 private:
  [[nodiscard]] bool continues(const Move& move) const;
  bool enabled_;
  std::vector<Move> run_;
};

}  // namespace kontur::program
