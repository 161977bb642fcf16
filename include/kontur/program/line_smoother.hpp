#pragma once
// Smoothing of dense G01 within the G64 tolerance: a streaming stage over the program's moves,
// before the corner blender. A run of feed lines (G1) joined without an exact stop, with the same
// positive tolerance (G64 P, else the machine's path tolerance; G64 Q when it is larger), turning
// by at most 30 degrees at each vertex (up to 90 between lines of a few tolerances, where the turn
// is noise within the tolerance: tolerances::smooth_soft_corner_*) and whose inner lines are at
// most 50 tolerances long, is
// replaced by one curvature-continuous curve (geometry/polyline_fit.hpp) within the tolerance of
// the programmed lines: its first and last line stay lines (the corners around the run are the
// blender's), each line between them becomes its piece of the curve (a move with the line's
// source line, feed and tag, and the programmed lines it replaces, which the checker measures
// every setpoint against). Collinear lines (every junction already smooth) stay lines. A run the
// fit cannot keep within the tolerance is halved, and each half fitted apart (a programmed corner
// between them), down to runs too short to smooth, which stay as programmed.
//
// The window is bounded: a run is cut after tolerances::smooth_max_run_lines lines. It is fitted
// with the lines after them up to tolerances::smooth_run_overlap_tolerances of arc length (at most
// smooth_run_overlap_max_lines), so that where it is cut the curve bends as
// the lines do; the next run continues the curve from there with its point, tangent and curvature
// (polyline_fit's start conditions), so the cut is curvature-continuous, not a corner of the
// programmed polyline. Where the curve's point at the cut is farther than the fit's share of the
// tolerance from the programmed vertex, the run ends there as a whole instead; where the next fit
// fails, its first line runs from the curve's point (within the tolerance of the programmed line).
#include <kontur/geometry/span_polynomial.hpp>
#include <kontur/program/move.hpp>
#include <limits>
#include <memory>
#include <optional>
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
  // The fitted curve of the run held back, with what its pieces need.
  struct Fitted {
    std::shared_ptr<const SpanPolynomialCurve> curve;
    std::vector<double> vertex_u;                         // parameter of each vertex of the fit
    std::shared_ptr<const std::vector<Vec3>> vertices;    // the programmed vertices it was fitted to
    double tolerance_mm = 0.0;
  };
  // Where the curve of a cut run ended: the next run starts there.
  struct Carry {
    Vec3 point, tangent, curvature;  // [mm], unit, [1/mm]
    double tolerance_mm = 0.0;
  };
  // The move is a feed line that continues the run (by its tolerance, length, place and turn).
  [[nodiscard]] bool joins(const Move& move) const;
  [[nodiscard]] std::optional<Fitted> fit_run() const;
  // Every junction of the run is already smooth for the planner (collinear lines, to rounding).
  [[nodiscard]] bool straight() const;
  void emit_pieces(const Fitted& f, std::size_t from, std::size_t to, std::vector<Move>& out);
  void as_programmed(std::vector<Move>& out);
  // A run whose fit failed: its halves are fitted apart, recursively (as programmed once too short).
  void split(std::vector<Move>& out);
  // The run's fit; none where the run was handed on instead (straight: as programmed; the fit
  // failed: split).
  [[nodiscard]] std::optional<Fitted> fit_or_hand_on(std::vector<Move>& out);
  // The whole run as a curve between its (fresh run) first and its last line, which stay lines.
  void emit_whole(const Fitted& f, std::vector<Move>& out);
  // Forget the run held back (handed on).
  void end_run();
  void cut(std::vector<Move>& out);
  bool enabled_;
  std::vector<Move> run_;
  std::optional<Carry> carry_;  // the run held back continues a cut run's curve
  double beyond_mm_ = 0.0;      // length of the run's lines after its first smooth_max_run_lines [mm]
  // length of the line the run's first line follows [mm] (infinite: none, or not joined to it)
  double before_run_mm_ = std::numeric_limits<double>::infinity();
};

}  // namespace kontur::program
