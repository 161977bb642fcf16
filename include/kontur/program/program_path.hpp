#pragma once
// The path a part program runs: each block becomes a move (move_of), runs of dense lines are
// smoothed within the G64 tolerance (LineSmoother), corners between lines are blended within it
// (CornerBlender), dwells stop the motion, and every move gets its id (its index in the path).
// One place, so that the pipeline, `kontur verify` and the tests see the same path.
#include <functional>
#include <kontur/gcode/block.hpp>
#include <kontur/gcode/reader.hpp>
#include <kontur/machine.hpp>
#include <kontur/program/corner_blender.hpp>
#include <kontur/program/line_smoother.hpp>
#include <kontur/program/move.hpp>
#include <string>
#include <vector>

namespace kontur::program {

/// What reading a program hands on, in program order. Any handler may be empty.
struct PathHandlers {
  std::function<void(const Move&)> move;           ///< a move of the path (its id set)
  std::function<void(const Dwell&)> dwell;         ///< a dwell, after the moves before it
  std::function<void(const gcode::Block&)> block;  ///< after each block's moves (progress)
};

class ProgramPath {
 public:
  /// `blend` false: corners are junctions (`--no-blend`); `smooth` false: runs of dense lines stay
  /// lines (`--no-smooth`); `speed` estimates how fast a blend runs and `junction` how fast a
  /// junction with an arc is passed without one (CornerBlender; without `speed` every corner within
  /// its tolerance is blended).
  ProgramPath(const Machine& machine, bool blend, bool smooth, BlendSpeed speed = {}, JunctionSpeed junction = {});
  ProgramPath(const ProgramPath&) = delete;
  ProgramPath& operator=(const ProgramPath&) = delete;

  /// Reads `program` (gcode::for_each_block: a program with an error yields nothing) and hands on
  /// its moves and dwells; the moves are kept (moves(), the same vector from one read to the next:
  /// each read starts it anew).
  /// `reader`: block delete and the dialect (none: detected).
  void read(const std::string& program, const PathHandlers& handlers, const gcode::ReaderOptions& reader = {});
  /// The same for a program already validated (gcode::validate_program): one reading pass.
  void read(const gcode::ValidatedProgram& program, const PathHandlers& handlers);

  /// The dialect the last read program was read in, and why.
  [[nodiscard]] const gcode::DialectChoice& dialect() const noexcept { return dialect_; }

  /// Every move of the path, in order: moves()[id].id == id.
  [[nodiscard]] const std::vector<Move>& moves() const noexcept { return moves_; }

 private:
  void take(std::vector<Move>& ready, const PathHandlers& handlers);

  const Machine& machine_;
  bool blend_;
  bool smooth_;
  BlendSpeed speed_;
  JunctionSpeed junction_;
  LineSmoother smoother_;
  CornerBlender blender_;
  std::vector<Move> smoothed_;  // moves out of the smoother, into the blender
  std::vector<Move> moves_;
  gcode::DialectChoice dialect_;
};

}  // namespace kontur::program
