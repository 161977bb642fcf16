#pragma once
// A move: what the program stage hands to planning and to the checker. Its geometry (a 3-D curve
// of the tool point), its feed, its corner tolerance, where it came from, and an id: its index in
// the program's path, so that every later stage (segments, setpoints, the checker, the summary)
// names the move it belongs to without guessing from source lines.
#include <cstdint>
#include <kontur/axes.hpp>
#include <kontur/geometry/curve.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace kontur::program {

/// Index of a move in its program's path (0, 1, 2, ... in path order).
using MoveId = std::uint32_t;
/// No move (a setpoint read from a file: the checker matches it by its source line).
inline constexpr MoveId no_move = std::numeric_limits<MoveId>::max();

/// The programmed corner a blend replaces: the programmed pieces on both sides of it, each a line
/// or a piece of an arc.
struct ProgrammedCorner {
  std::shared_ptr<const Curve> before;  ///< the incoming move, as programmed, up to the corner
  std::shared_ptr<const Curve> after;   ///< the outgoing move, as programmed, from the corner
  double tolerance_mm = 0.0;            ///< the G64 tolerance the blend must keep [mm]
};

/// The programmed lines a smoothed line's curve replaces (program/line_smoother.hpp): the run's
/// vertices, shared by its moves, and which of its lines this move is.
struct ProgrammedLines {
  std::shared_ptr<const std::vector<Vec3>> vertices;  ///< the run's programmed vertices [mm]
  std::size_t line = 0;                               ///< this move's line: vertices[line] -> vertices[line + 1]
  double tolerance_mm = 0.0;                          ///< the G64 tolerance the curve must keep [mm]
};

/// One move of the path.
struct Move {
  MoveId id = no_move;                  ///< index in the path (set when the move leaves the program stage)
  std::shared_ptr<const Curve> curve;   ///< the tool path [mm] (shared: planning keeps it while needed)
  double feed_mm_s = 0.0;               ///< programmed path speed [mm/s] (rapid: the machine's rapid feed)
  bool exact_stop = false;              ///< stop at its end (G61 / G61.1)
  double corner_tolerance_mm = 0.0;     ///< G64 tolerance at its end [mm] (0: no blending there)
  double naive_cam_tolerance_mm = 0.0;  ///< G64 Q [mm] (0: none given; smoothing keeps the larger of P and Q)
  long source_line = 0;                 ///< line of the program it comes from (a blend: the outgoing block's)
  const char* type = "";                ///< the block's type name ("line", "arc", ...; "blend" for a corner blend)
  /// Its path length as run: the distance the feed applies to and the planner's path parameter runs
  /// over (LinuxCNC's rule): the tool path's length [mm] when X Y Z move, else the U V W distance
  /// [mm], else the A B C angle [deg].
  double length_mm = 0.0;
  /// A B C [deg] and U V W [mm] at its start and end; they move linearly with the path distance.
  ExtraAxes extra_start{}, extra_end{};
  /// True if the tool point stands still (only extra axes move): the curve is a point.
  bool tool_still = false;
  /// A corner blend: the programmed corner it replaces (checked against its tolerance).
  std::optional<ProgrammedCorner> corner;
  /// A smoothed line: the programmed lines around it (checked against their tolerance).
  std::optional<ProgrammedLines> lines;
};

/// True if any of A B C U V W moves on `m`.
[[nodiscard]] inline bool moves_extra_axes(const Move& m) noexcept { return m.extra_start != m.extra_end; }

/// The extra axes at distance `s_mm` along `m` (0 <= s <= length_mm): exactly extra_start at 0 and
/// extra_end at length_mm.
[[nodiscard]] ExtraAxes extra_at(const Move& m, double s_mm) noexcept;

/// The path length of a move (Move::length_mm) from its tool path's length [mm] and its extra axes:
/// the tool path's when it is longer than tolerances::extra_axes_tool_still_mm, else the U V W
/// distance, else the A B C angle; `tool_still` tells which.
[[nodiscard]] double path_length(double tool_length_mm, const ExtraAxes& from, const ExtraAxes& to,
                                 bool& tool_still) noexcept;

/// A move along `curve` at `feed_mm_s` [mm/s] (its length computed; type "curve"; no id), for
/// callers that make moves without a program.
[[nodiscard]] Move move_along(std::shared_ptr<const Curve> curve, double feed_mm_s, bool exact_stop = false,
                              long source_line = 0);

/// A dwell (G4): the motion stops at the end of the moves before it and stays there.
struct Dwell {
  double seconds = 0.0;  ///< [s]
  long source_line = 0;  ///< line of the G4 block
};

}  // namespace kontur::program
