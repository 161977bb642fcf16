#pragma once
// A move: what the program stage hands to planning and to the checker. Its geometry (a 3-D curve
// of the tool point), its feed, its corner tolerance, where it came from, and an id: its index in
// the program's path, so that every later stage (segments, setpoints, the checker, the summary)
// names the move it belongs to without guessing from source lines.
#include <cstdint>
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

/// The programmed corner a blend replaces: the lines before -> corner -> after of the program.
struct ProgrammedCorner {
  Vec3 before = Vec3::Zero();  ///< start of the incoming line [mm]
  Vec3 corner = Vec3::Zero();  ///< the corner point [mm]
  Vec3 after = Vec3::Zero();   ///< end of the outgoing line [mm]
  double tolerance_mm = 0.0;   ///< the G64 tolerance the blend must keep [mm]
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
  double length_mm = 0.0;               ///< its length as run [mm]
  /// A corner blend: the programmed corner it replaces (checked against its tolerance).
  std::optional<ProgrammedCorner> corner;
  /// A smoothed line: the programmed lines around it (checked against their tolerance).
  std::optional<ProgrammedLines> lines;
};

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
