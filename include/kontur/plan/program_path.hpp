#pragma once
// The path a part program runs, as `kontur run` plans it and `kontur verify` checks it: each block
// becomes a move (plan::move_input), corners between lines are blended within the G64 tolerance
// (CornerBlender), and dwells stop the motion. One place, so that the planner, the check and the
// tests see the same path.
#include <kontur/gcode/block.hpp>
#include <kontur/machine.hpp>
#include <kontur/plan/corner_blend.hpp>
#include <kontur/plan/motion_planner.hpp>
#include <kontur/verify/checker.hpp>

#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace kontur::plan {

/// One move of the path, in order.
struct PathEntry {
  MoveInput move;            ///< curve, feed [mm/s], exact stop, source line
  const char* type = "";     ///< the block's type name (gcode::to_string), or "blend"
  double length_mm = 0.0;    ///< length of the move as run [mm]
};

/// What reading a program hands on, in program order.
struct ProgramEvents {
  std::function<void(const MoveInput&)> move;                  ///< a move to plan
  std::function<void(double seconds, long source_line)> dwell; ///< a dwell, after the moves before it
  std::function<void(const gcode::Block&)> block;              ///< after each block's moves (progress, draining)
};

class ProgramPath {
public:
  /// `blend` false: corners are junctions (`--no-blend`).
  ProgramPath(const Machine& machine, bool blend);
  ProgramPath(const ProgramPath&) = delete;
  ProgramPath& operator=(const ProgramPath&) = delete;

  /// Reads `program` (gcode::for_each_block: a program with an error yields nothing) and hands on
  /// its moves and dwells; the path is kept (entries(), check_moves()). Any event may be empty.
  void read(const std::string& program, const ProgramEvents& events);

  /// Every move of the path, in order.
  [[nodiscard]] const std::vector<PathEntry>& entries() const noexcept { return entries_; }
  /// The same as the checker takes them (blends with the programmed corner they replace).
  [[nodiscard]] const std::vector<verify::PathMove>& check_moves() const noexcept { return check_moves_; }

private:
  void take(std::vector<BlendedMove>& ready, const ProgramEvents& events);

  const Machine& machine_;
  CornerBlender blender_;
  struct BlockInfo {
    const char* type;
    double length_mm;
    const Curve* curve;
  };
  std::vector<BlockInfo> blocks_;                 // per block with a move (the blender's tag)
  std::vector<PathEntry> entries_;
  std::deque<verify::ProgrammedCorner> corners_;  // stable addresses for check_moves_
  std::vector<verify::PathMove> check_moves_;
};

}  // namespace kontur::plan
